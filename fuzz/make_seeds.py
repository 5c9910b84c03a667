"""Writes the generated seed files of fuzz/corpus/ (tiny videos and images, the structured-mode
and API seeds); the text seeds are written by hand. Run once; the outputs are committed.

    .venv/bin/python fuzz/make_seeds.py
"""

from __future__ import annotations

import os
import random
import tempfile

import cv2
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
KINDS = [".avi", ".mp4", ".mkv", "png", "jpg", "bmp"]  # fuzz_video.py: first byte % 6


def video_bytes(ext: str, fourcc: str, frames: int, size=(32, 24)) -> bytes:
    rng = np.random.default_rng(0)
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "v" + ext)
        w = cv2.VideoWriter(path, cv2.VideoWriter_fourcc(*fourcc), 10, size)
        for _ in range(frames):
            w.write(rng.integers(0, 255, (size[1], size[0], 3), dtype=np.uint8))
        w.release()
        return open(path, "rb").read()


def write(folder: str, name: str, data: bytes) -> None:
    os.makedirs(os.path.join(HERE, "corpus", folder), exist_ok=True)
    with open(os.path.join(HERE, "corpus", folder, name), "wb") as f:
        f.write(data)


def main() -> None:
    avi = video_bytes(".avi", "MJPG", 3)
    write("video", "mjpg.avi", bytes([KINDS.index(".avi")]) + avi)
    write("video", "truncated.avi", bytes([KINDS.index(".avi")]) + avi[: len(avi) * 2 // 3])
    write("video", "mp4v.mp4", bytes([KINDS.index(".mp4")]) + video_bytes(".mp4", "mp4v", 3))
    write("video", "mjpg.mkv", bytes([KINDS.index(".mkv")]) + video_bytes(".mkv", "MJPG", 2))
    img = np.random.default_rng(1).integers(0, 255, (24, 32, 3), dtype=np.uint8)
    for ext in ("png", "jpg", "bmp"):
        ok, enc = cv2.imencode("." + ext, img)
        assert ok
        # bit 4: a second, identical image (a two-frame folder); bit 3: a truncated copy.
        write("video", f"one.{ext}", bytes([KINDS.index(ext)]) + enc.tobytes())
        write("video", f"two.{ext}", bytes([KINDS.index(ext) + 6 * 3]) + enc.tobytes())
    write("video", "png_and_truncated.png", bytes([KINDS.index("png") + 6 * 2]) +
          cv2.imencode(".png", img)[1].tobytes())
    rnd = random.Random(0)
    for i in range(4):
        write("detections", f"structured_{i}.bin", b"\xf0" + rnd.randbytes(96))
        write("config", f"structured_{i}.bin", b"\xf0" + rnd.randbytes(96))
    for i in range(24):
        write("api", f"seed_{i:02d}.bin", rnd.randbytes(rnd.randint(16, 400)))


if __name__ == "__main__":
    main()

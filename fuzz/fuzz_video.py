"""Fuzz the video prober (vtrack.io.probe_video, behind `vtrack info`) and, on the small videos
it accepts, the whole mb pipeline (vtrack.track_video): a container or image that is truncated,
corrupt or lies about its size must give OSError/ValueError naming the frame, never a crash.

The input's first byte picks the container (.avi, .mp4, .mkv) or an image folder (.png, .jpg,
.bmp files, one to three of them); the rest is the file's bytes, mutated from the seeds in
fuzz/corpus/video/ (tiny valid videos and images written by OpenCV).

    .venv/bin/python fuzz/fuzz_video.py -max_total_time=60 fuzz/corpus/video
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile

import atheris

# Coverage feedback from vtrack's Python code only: the compiled module is not instrumented, and
# instrumenting NumPy and OpenCV's Python parts took ~20 s per harness start for nothing.
with atheris.instrument_imports(include=["vtrack"]):
    import vtrack

from _common import SCRATCH, check, scratch_file

KINDS = [".avi", ".mp4", ".mkv", "png", "jpg", "bmp"]


def probe_and_track(path: str) -> None:
    info = None

    def probe():
        nonlocal info
        info = vtrack.io.probe_video(path)

    check(probe)
    if info is not None and info.frame_count <= 8 and info.width * info.height <= 128 * 128:
        check(lambda: vtrack.track_video(path, method="mb", n_samples=2, max_particles=50,
                                         birth_particles=20, min_particles=10))


def one_input(data: bytes) -> None:
    if not data:
        return
    kind = KINDS[data[0] % len(KINDS)]
    body = data[1:]
    if kind.startswith("."):
        with scratch_file(body, kind) as path:
            probe_and_track(path)
        return
    folder = tempfile.mkdtemp(dir=SCRATCH)
    try:
        # The image, then (by the first byte's bits) a truncated copy and a whole copy.
        parts = [body] + ([body[: len(body) // 2]] if data[0] & 8 else []) + \
            ([body] if data[0] & 16 else [])
        for i, part in enumerate(parts):
            with open(os.path.join(folder, f"{i:03d}.{kind}"), "wb") as f:
                f.write(part)
        probe_and_track(folder)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def main() -> None:
    atheris.Setup(sys.argv, one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()

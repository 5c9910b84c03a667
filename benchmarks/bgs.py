"""Speed of background subtraction on the sample video: vtrack's KDE (eq. 10) against OpenCV's
MOG2 and KNN, BGSLibrary's KDE (PyPI ``pybgs``, skipped when not installed) and the NumPy
float64 transcription of eq. (10) (vtrack.reference).

The video is decoded into memory once; every method then runs over the same frames, in rounds
(each round runs every method once, in turn, so slow drifts of the machine's load hit all
methods alike). Reported: the median over rounds of the frames per second of a whole pass,
megapixels per second, and the ratio to vtrack's KDE with the same thread setting.
Single-thread rows use ``threads=1`` for vtrack and ``cv2.setNumThreads(1)`` for OpenCV.

    python benchmarks/bgs.py [--video PATH] [--frames N] [--rounds R] [--numpy-frames M]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import cv2
import numpy as np

import vtrack
from vtrack.reference import KdeBackgroundReference

N0 = 10  # the bar: N0 = 10 samples
K0 = 10


def default_video() -> str:
    return os.environ.get("VTRACK_VIDEO", str(Path.home() / ".cache" / "vtrack" / "vtest.avi"))


def decode(path: str, limit: int) -> list:
    cap = cv2.VideoCapture(path)
    frames = []
    while len(frames) < limit:
        ok, frame = cap.read()
        if not ok:
            break
        frames.append(frame)
    if not frames:
        sys.exit(f"cannot decode {path}")
    return frames


def time_pass(make, frames, threads: int) -> float:
    """Seconds for one pass of a fresh model over the frames."""
    cv2.setNumThreads(1 if threads == 1 else -1)
    apply = make()
    start = time.perf_counter()
    for frame in frames:
        apply(frame)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--video", default=default_video())
    parser.add_argument("--frames", type=int, default=795, help="frames decoded (default: all 795)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--numpy-frames", type=int, default=30,
                        help="frames for the slow NumPy transcription (default 30)")
    args = parser.parse_args()

    frames = decode(args.video, args.frames)
    h, w = frames[0].shape[:2]
    mp = h * w / 1e6
    default_threads = cv2.getNumThreads()
    print(f"{len(frames)} frames of {w}x{h} from {args.video}; N0={N0}, K0={K0}; "
          f"{args.rounds} rounds; default threads = {default_threads} (cv2), {os.cpu_count()} CPUs\n")

    def vtrack_kde(threads):
        return lambda: vtrack.KdeBackground(n_samples=N0, period=K0, closing=0, threads=threads).apply

    def vtrack_kde_closing(threads):
        return lambda: vtrack.KdeBackground(n_samples=N0, period=K0, closing=3, threads=threads).apply

    methods = []  # (name, threads label, factory, frames)
    for threads in (1, 0):
        label = "1" if threads == 1 else f"default ({default_threads})"
        methods += [
            ("vtrack KDE", label, vtrack_kde(threads), frames),
            ("vtrack KDE + closing 3x3", label, vtrack_kde_closing(threads), frames),
            ("OpenCV MOG2", label, lambda: cv2.createBackgroundSubtractorMOG2().apply, frames),
            ("OpenCV KNN", label, lambda: cv2.createBackgroundSubtractorKNN().apply, frames),
        ]
    try:
        import pybgs  # noqa: F401

        # BGSLibrary's KDE (Elgammal): its own parameters (adaptive bandwidth, 50 samples
        # by default); it runs on one thread whatever cv2's setting.
        methods.append(("BGSLibrary KDE (pybgs)", "1", lambda: pybgs.KDE().apply, frames))
    except ImportError as exc:
        print(f"pybgs not available ({exc}); its row is skipped\n")
    numpy_frames = frames[: args.numpy_frames]
    methods.append(("NumPy transcription (float64)", "1",
                    lambda: KdeBackgroundReference(N0, K0, (0.02, 0.02, 0.06)).apply, numpy_frames))

    times = {(name, label): [] for name, label, _, _ in methods}
    for _ in range(args.rounds):
        for name, label, make, subset in methods:
            threads = 1 if label == "1" else 0
            times[(name, label)].append(len(subset) / time_pass(make, subset, threads))

    fps = {key: statistics.median(v) for key, v in times.items()}
    base = {label: fps[("vtrack KDE", label)] for _, label, _, _ in methods if ("vtrack KDE", label) in fps}
    print("| method | threads | frames | median frames/s | MP/s | vtrack KDE / method |")
    print("|---|---|---|---:|---:|---:|")
    for name, label, _, subset in methods:
        f = fps[(name, label)]
        ref = base.get(label, base["1"])
        print(f"| {name} | {label} | {len(subset)} | {f:.1f} | {f * mp:.1f} | {ref / f:.2f} |")
    print("\nvtrack KDE uses closing=0 unless stated; the ratio compares with vtrack KDE at the same "
          "thread setting (single-thread vtrack for the single-thread-only peers).")


if __name__ == "__main__":
    main()

"""Speed of background subtraction on the sample video: vtrack's KDE (eq. 10) against OpenCV's
MOG2 and KNN, BGSLibrary's KDE (PyPI ``pybgs``, skipped when not installed) and the NumPy
float64 transcription of eq. (10) (vtrack.reference).

The video is decoded into memory once. Each method gets a fresh model, is fed the first
N0*K0 = 100 frames untimed (so vtrack's sample stack is full, as in steady state), and is then
timed over the remaining frames. This runs in rounds (each round runs every method once, in
turn, so drifts of the machine's load hit all methods alike). Reported: the median over rounds of
frames per second by wall clock and by process CPU time (robust when other jobs share the cores;
for multi-threaded rows CPU time counts all threads), megapixels per second (wall), and the
ratio of vtrack's KDE to the method at the same thread setting (> 1: vtrack is faster).
Single-thread rows use ``threads=1`` for vtrack and ``cv2.setNumThreads(1)`` for OpenCV (vtrack
links the system OpenCV, a separate copy from cv2's, so cv2's setting does not reach it: its own
``threads`` parameter decides; BGSLibrary's KDE is single-threaded code).
The NumPy transcription is too slow for the whole video: it is fed N0 frames with K0 = 1 (a
full stack; its per-frame work is the same for any K0) and timed on the next --numpy-frames.

    python benchmarks/bgs.py [--video PATH] [--frames N] [--rounds R] [--numpy-frames M]
"""

from __future__ import annotations

import argparse
import contextlib
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import cv2
import numpy as np

import vtrack
from vtrack.reference import KdeBackgroundReference

N0 = 10  # the bar: N0 = 10 samples
K0 = 10
BANDWIDTH = (0.03, 0.03, 0.06)  # vtrack's defaults (sigma_r, sigma_g, sigma_I)


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


def time_pass(make, warmup, frames, threads: int):
    """(wall seconds, CPU seconds) of a fresh model over `frames` after the untimed `warmup`."""
    cv2.setNumThreads(1 if threads == 1 else -1)
    apply = make()
    for frame in warmup:
        apply(frame)
    wall, cpu = time.perf_counter(), time.process_time()
    for frame in frames:
        apply(frame)
    return time.perf_counter() - wall, time.process_time() - cpu


@contextlib.contextmanager
def pybgs_sandbox():
    """pybgs prints from C++ on every construction and writes ./config/<Method>.xml: run it in a
    scratch directory with the process's stdout and stderr sent to /dev/null."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2), os.getcwd()
    with tempfile.TemporaryDirectory() as scratch, open(os.devnull, "w") as null:
        os.makedirs(os.path.join(scratch, "config"))
        os.chdir(scratch)
        os.dup2(null.fileno(), 1)
        os.dup2(null.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.chdir(saved[2])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--video", default=default_video())
    parser.add_argument("--frames", type=int, default=795, help="frames decoded (default: all 795)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--numpy-frames", type=int, default=10,
                        help="frames timed for the slow NumPy transcription (default 10)")
    parser.add_argument("--skip", default="", help="comma-separated substrings of methods to skip")
    args = parser.parse_args()

    frames = decode(args.video, args.frames)
    h, w = frames[0].shape[:2]
    mp = h * w / 1e6
    warm = N0 * K0
    default_threads = cv2.getNumThreads()
    print(f"{len(frames)} frames of {w}x{h} from {args.video}: {warm} untimed warm-up frames, "
          f"{len(frames) - warm} timed; N0={N0}, K0={K0}, bandwidth {BANDWIDTH}; {args.rounds} rounds; "
          f"default threads = {default_threads} (cv2), {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.1f} at start\n")

    def vtrack_kde(threads, closing):
        return lambda: vtrack.KdeBackground(n_samples=N0, period=K0, bandwidth=BANDWIDTH,
                                            closing=closing, threads=threads).apply

    def opencv(factory):
        return lambda: factory().apply

    # (name, threads label, model factory, warm-up frames, timed frames, context)
    methods = []
    full = (frames[:warm], frames[warm:], contextlib.nullcontext)
    for threads in (1, 0):
        label = "1" if threads == 1 else f"default ({default_threads})"
        methods += [
            ("vtrack KDE", label, vtrack_kde(threads, 0), *full),
            ("vtrack KDE + closing 3x3", label, vtrack_kde(threads, 3), *full),
            ("OpenCV MOG2", label, opencv(cv2.createBackgroundSubtractorMOG2), *full),
            ("OpenCV KNN", label, opencv(cv2.createBackgroundSubtractorKNN), *full),
        ]
    try:
        import pybgs

        # BGSLibrary's KDE (Elgammal et al.) with its own defaults; single-threaded code.
        methods.append(("BGSLibrary KDE (pybgs)", "1", lambda: pybgs.KDE().apply,
                        frames[:warm], frames[warm:], pybgs_sandbox))
    except ImportError as exc:
        print(f"pybgs not available ({exc}): its row is skipped (make bench installs it)\n")
    methods.append(("NumPy transcription (float64)", "1",
                    lambda: KdeBackgroundReference(N0, 1, BANDWIDTH).apply,
                    frames[:N0], frames[N0:N0 + args.numpy_frames], contextlib.nullcontext))
    skip = [x for x in args.skip.split(",") if x]
    methods = [m for m in methods if not any(x in m[0] for x in skip)]

    wall = {m[:2]: [] for m in methods}
    cpu = {m[:2]: [] for m in methods}
    for _ in range(args.rounds):
        for name, label, make, warmup, timed, context in methods:
            with context():
                t_wall, t_cpu = time_pass(make, warmup, timed, 1 if label == "1" else 0)
            wall[(name, label)].append(len(timed) / t_wall)
            cpu[(name, label)].append(len(timed) / t_cpu)

    fps = {key: statistics.median(v) for key, v in wall.items()}
    fps_cpu = {key: statistics.median(v) for key, v in cpu.items()}
    print("| method | threads | timed frames | frames/s (wall) | MP/s (wall) | frames/s (CPU time) "
          "| vtrack KDE / method (wall) | (CPU) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name, label, _, _, timed, _ in methods:
        ref_key = ("vtrack KDE", label) if ("vtrack KDE", label) in fps else ("vtrack KDE", "1")
        f, c = fps[(name, label)], fps_cpu[(name, label)]
        ratio = f"{fps[ref_key] / f:.2f}" if ref_key in fps else "-"
        ratio_cpu = f"{fps_cpu[ref_key] / c:.2f}" if ref_key in fps_cpu else "-"
        print(f"| {name} | {label} | {len(timed)} | {f:.1f} | {f * mp:.1f} | {c:.1f} | {ratio} | {ratio_cpu} |")
    print(f"\nload average {os.getloadavg()[0]:.1f} at the end. vtrack KDE rows without closing "
          "unless stated. Ratios are against vtrack KDE at the same thread setting (single-thread "
          "vtrack KDE for the single-thread-only peers).")


if __name__ == "__main__":
    main()

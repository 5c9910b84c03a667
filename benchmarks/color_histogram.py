"""Speed of scoring particle boxes against a color template (part-based paper eqs. 9-10): the
two ways vtrack.image.ColorModel.coefficients can count the boxes' 16 x 4 x 4 HSV histograms, the
kernel-weighted count, and NumPy peers, on a real frame of vtest.avi.

Each call scores N boxes around a person-sized box of w x h pixels, as a particle filter does
once per frame: convert the region holding every box to bin indices (once), count each box's
histogram, compute its Bhattacharyya coefficient. Box sizes 20 x 50 to 100 x 250, N = 30, 90,
210 (the paper's Table 1), and two spreads of the boxes: "tight" (centres N(0, 2 px), sizes
N(0, 1 px): a particle cloud after a few frames of tracking) and "wide" (centres N(0, 0.15 w)
and N(0, 0.15 h), sizes N(0, 0.05 w / h): right after a jump, or a lost track). Methods:

* direct: each box's pixels, one increment per pixel (four partial histograms);
* incremental: boxes in a greedy chain (each next box the one that differs least from the last
  among the next 64 in Morton order of their corners), each box's counts updated from the
  previous box's by the pixels that differ (a direct count when that is not cheaper); the
  default ('auto');
* kernel direct / kernel incremental: the same two with Nummiaro's Epanechnikov weights (direct:
  a double weight per pixel; incremental: per-bin moments of the pixels' coordinates, from which
  the weights follow, updated by the pixels that differ; the default for kernel=True);
* NumPy: cv2.cvtColor of the region once, then one np.bincount per box over its slice (the
  histogram code of benchmarks/follow.py's NumPy particle filter), the Bhattacharyya
  coefficient as one matrix product;
* NumPy per-box cvtColor + calcHist: the naive way, converting every box.

Measured (this script, 2 cores shared with other jobs, CPU time, frame 100; microseconds per
call): direct / incremental / kernel / NumPy / per-box calcHist at 20x50, N = 30, tight: 40 / 21 /
75 / 263 / 1419; 40x100, N = 90, tight 232 / 63 / 660 / 1318 / 4686, wide 252 / 158 / 716 / 1357 /
4529; 60x150, N = 210, tight 1087 / 156 / 3167 / 5294 / 21725; 100x250, N = 210, tight 2852 / 326
/ 11379 / 15513 / 49882, wide 3042 / 1785 / 8675 / 14550 / 44442. NumPy over vtrack: 3.2-9.8x for
direct counts, 5.5-48x for incremental ones (5.5-9x on wide clouds, 12-48x on tight ones).
Incremental counting beat direct counting in all 24 cases, so ColorModel uses it by default. The
kernel-weighted count costs 2-4x the direct one (a double weight per pixel).

After issue 11's speed work (greedy chain; kernel-weighted histograms counted incrementally
through per-bin coordinate moments), same machine, CPU us per call, direct / incremental / kernel
direct / kernel incremental / NumPy: 20x50, N = 30, tight 37 / 25 / 99 / 34 / 240; 40x100, N =
90, tight 230 / 64 / 638 / 98 / 1825, wide 334 / 188 / 852 / 266 / 1350; 60x150, N = 210, tight
980 / 162 / 4763 / 261 / 5154; 100x250, N = 210, tight 2756 / 284 / 9682 / 585 / 11410, wide 2972
/ 1400 / 9739 / 1784 / 16262. The incremental kernel-weighted count costs 0.8-2.3x (mostly
1.3-1.7x) the unweighted incremental one and is 2-18x faster than the direct kernel-weighted count
in all 24 cases.

An integral histogram over the region (one summed-area table per bin, then 4 lookups per bin per
box) was measured as a third method in commit 2754c4f (then with cv::cvtColor and scalar sums, so
all figures were higher): direct / incremental / integral 61 / 44 / 159 at 20x50, N = 30, tight;
402 / 144 / 566 at 40x100, N = 90, tight, 441 / 262 / 2101 wide; 4471 / 464 / 5964 at 100x250, N
= 210, tight, 3616 / 2427 / 89462 wide. It never won: building it costs (region pixels) x 256
adds, more than counting all N <= 210 boxes directly when the region is not much larger than a
box, and far more for wide clouds; it was removed.

Times are medians of repeated calls in CPU time of the calling thread (time.thread_time: robust
when other jobs share the cores; everything here runs on that one thread: cv2.setNumThreads(1),
one-thread BLAS, and vtrack's color code is single-threaded); the ratio columns are NumPy's time
over the method's.

    python benchmarks/color_histogram.py [--video PATH] [--frame K] [--repeats R]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import cv2  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
from _table import median_seconds, print_table  # noqa: E402

import vtrack  # noqa: E402

SIZES = [(20, 50), (40, 100), (60, 150), (100, 250)]
COUNTS = [30, 90, 210]
CENTRE = (400, 300)  # a person-free area is not needed: any real texture will do


def default_video() -> str:
    return os.environ.get("VTRACK_VIDEO", str(Path.home() / ".cache" / "vtrack" / "vtest.avi"))


def read_frame(path: str, index: int) -> np.ndarray:
    cap = cv2.VideoCapture(path)
    frame = None
    for _ in range(index + 1):
        ok, frame = cap.read()
        if not ok:
            sys.exit(f"cannot decode frame {index} of {path}")
    return frame


def particle_boxes(rng, n: int, w: int, h: int, spread: str) -> np.ndarray:
    if spread == "tight":
        s_pos, s_size = (2.0, 2.0), (1.0, 1.0)
    else:
        s_pos, s_size = (0.15 * w, 0.15 * h), (0.05 * w, 0.05 * h)
    cx = CENTRE[0] + rng.normal(0, s_pos[0], n)
    cy = CENTRE[1] + rng.normal(0, s_pos[1], n)
    bw = np.maximum(w + rng.normal(0, s_size[0], n), 2)
    bh = np.maximum(h + rng.normal(0, s_size[1], n), 2)
    return np.column_stack([cx - bw / 2, cy - bh / 2, bw, bh])


class NumpyScorer:
    """The histogram scoring of benchmarks/follow.py's NumPy particle filter."""

    def __init__(self, frame, box):
        c = np.arange(256)
        self.lut = (c * 16 // 256 * 16, c * 4 // 256 * 4, c * 4 // 256)
        q = self.histograms(frame, np.asarray([box]))[0]
        self.sqrt_q = np.sqrt(q)

    def histograms(self, frame, boxes):
        x0 = np.floor(boxes[:, 0] + 0.5).astype(int)
        y0 = np.floor(boxes[:, 1] + 0.5).astype(int)
        x1 = np.floor(boxes[:, 0] + boxes[:, 2] + 0.5).astype(int)
        y1 = np.floor(boxes[:, 1] + boxes[:, 3] + 0.5).astype(int)
        rx0, ry0 = x0.min(), y0.min()
        hsv = cv2.cvtColor(frame[ry0:y1.max(), rx0:x1.max()], cv2.COLOR_BGR2HSV_FULL)
        bins = self.lut[0][hsv[..., 0]] + self.lut[1][hsv[..., 1]] + self.lut[2][hsv[..., 2]]
        out = np.empty((len(boxes), 256))
        for i in range(len(boxes)):
            out[i] = np.bincount(bins[y0[i] - ry0:y1[i] - ry0, x0[i] - rx0:x1[i] - rx0].ravel(),
                                 minlength=256)
        return out / ((x1 - x0) * (y1 - y0))[:, None]

    def coefficients(self, frame, boxes):
        return np.sqrt(self.histograms(frame, boxes)) @ self.sqrt_q


def calchist_coefficients(frame, boxes, q):
    """Per box: crop, cvtColor, calcHist (16 x 4 x 4 over HSV_FULL), normalise, compare."""
    out = np.empty(len(boxes))
    for i, (x, y, w, h) in enumerate(np.floor(boxes + 0.5).astype(int)):
        hsv = cv2.cvtColor(frame[y:y + h, x:x + w], cv2.COLOR_BGR2HSV_FULL)
        hist = cv2.calcHist([hsv], [0, 1, 2], None, [16, 4, 4], [0, 256, 0, 256, 0, 256]).ravel()
        out[i] = np.sum(np.sqrt(hist / hist.sum() * q))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--video", default=default_video())
    parser.add_argument("--frame", type=int, default=100)
    parser.add_argument("--repeats", type=int, default=9)
    args = parser.parse_args()
    cv2.setNumThreads(1)
    frame = read_frame(args.video, args.frame)
    rng = np.random.default_rng(0)
    header = ["boxes", "N", "spread", "direct us", "incremental us", "kernel direct us",
              "kernel incremental us", "NumPy us", "calcHist us", "NumPy / direct",
              "NumPy / incremental"]
    rows = []
    for w, h in SIZES:
        box = (CENTRE[0] - w / 2, CENTRE[1] - h / 2, w, h)
        model = vtrack.image.ColorModel(frame, box)
        kernel = vtrack.image.ColorModel(frame, box, kernel=True)
        numpy_scorer = NumpyScorer(frame, box)
        q = model.reference.ravel()
        for n in COUNTS:
            for spread in ("tight", "wide"):
                boxes = particle_boxes(rng, n, w, h, spread)
                ref = model.coefficients(frame, boxes)
                direct = model.coefficients(frame, boxes, method="direct")
                assert np.allclose(direct, ref, atol=1e-5)
                assert np.allclose(kernel.coefficients(frame, boxes, method="direct"),
                                   kernel.coefficients(frame, boxes, method="incremental"),
                                   atol=1e-9)
                assert np.allclose(numpy_scorer.coefficients(frame, boxes), ref, atol=1e-5)
                calls = {
                    "direct": lambda: model.coefficients(frame, boxes, method="direct"),
                    "incremental": lambda: model.coefficients(frame, boxes, method="incremental"),
                    "kernel direct": lambda: kernel.coefficients(frame, boxes, method="direct"),
                    "kernel incremental": lambda: kernel.coefficients(frame, boxes,
                                                                      method="incremental"),
                    "numpy": lambda: numpy_scorer.coefficients(frame, boxes),
                    "calchist": lambda: calchist_coefficients(frame, boxes, q),
                }
                t = {name: median_seconds(call, clock=time.thread_time,
                                          repeats=args.repeats if name != "calchist" else 3)
                     for name, call in calls.items()}
                rows.append([f"{w}x{h}", n, spread, *(f"{1e6 * t[m]:.0f}" for m in calls),
                             f"{t['numpy'] / t['direct']:.1f}",
                             f"{t['numpy'] / t['incremental']:.1f}"])
    print(f"Scoring N boxes against a template on frame {args.frame} of {Path(args.video).name} "
          "(median CPU microseconds per call, one thread)")
    print()
    print_table(header, rows)


if __name__ == "__main__":
    main()

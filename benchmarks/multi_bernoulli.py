"""Multi-Bernoulli TBD filter speed per frame at 768 x 576, against a NumPy peer and the budget.

Usage: python benchmarks/multi_bernoulli.py [--frames N]
The tracker runs with its defaults on rendered background-subtraction images y of a synthetic
PETS-like scene (six people in view in the timed frames). Each row gives the median time of
`step(y)` per frame over the timed frames. The NumPy peer does the least any NumPy version of the
same update must do per frame: the integral image of y (np.cumsum) and eq. (20) for as many
particles as the tracker holds, vectorised. The issue's budget is 20 ms per frame (50 frames/s)
for background subtraction and filter together, one core.
"""

import argparse
import os
import sys
import time
from statistics import median

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _table import print_table  # noqa: E402

import vtrack  # noqa: E402
from vtrack.synthetic import make_scene, render_y  # noqa: E402


def numpy_peer(y, boxes, delta_f=0.1, delta_b=1e-3):
    """Integral image and log g_y of eq. (20) for each box (n, 4 ints: x0, y0, x1, y1)."""
    h, w = y.shape
    table = np.zeros((h + 1, w + 1))
    table[1:, 1:] = np.cumsum(np.cumsum(y, axis=0, dtype=np.float64), axis=1)
    x0, y0, x1, y1 = boxes.T
    s = table[y1, x1] - table[y0, x1] - table[y1, x0] + table[y0, x0]
    m_x = np.maximum((x1 - x0) * (y1 - y0), 1)
    ybar = s / m_x
    log_zeta = -np.log(delta_f) - np.log1p(-np.exp(-1 / delta_f))
    return (m_x - s) / (h * w * delta_b) + log_zeta - ybar / delta_f


def time_tracker(ys, first, **params):
    tracker = vtrack.MultiBernoulliTracker((768, 576), seed=0, **params)
    times, particles, tracks = [], [], []
    for k, y in enumerate(ys):
        start = time.perf_counter()
        out = tracker.step(y)
        elapsed = time.perf_counter() - start
        if k >= first:
            times.append(elapsed)
            particles.append(sum(len(c.weights) for c in tracker.components))
            tracks.append(len(out))
    return median(times), int(median(particles)), int(median(tracks))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=60)
    args = parser.parse_args()
    scene = make_scene(768, 576, n_frames=330, n_people=6, seed=1, size=((25, 60), (70, 140)),
                       speed=(3.0, 5.0), enter_within=100)
    start = 110  # everyone is in view from frame ~80 to ~190
    rng = np.random.default_rng(0)
    ys = [render_y(scene.mask(k), rng) for k in range(start + args.frames)]

    rows = []
    for name, params in (("defaults", {}),
                         ("no closing", {"closing_size": 0}),
                         ("no data-driven birth", {"adaptive_birth": False}),
                         ("no quarter birth", {"quarter_birth": False})):
        t, n, k = time_tracker(ys, start, **params)
        rows.append([name, k, n, f"{t * 1e3:.2f}", f"{1 / t:.0f}"])
    t_vtrack = float(rows[0][3]) / 1e3
    n = rows[0][2]
    rng = np.random.default_rng(1)
    x0 = rng.integers(0, 700, n)
    y0 = rng.integers(0, 450, n)
    boxes = np.stack([x0, y0, x0 + rng.integers(20, 60, n), y0 + rng.integers(60, 120, n)], 1)
    y = ys[start]
    samples = []
    for _ in range(15):
        t0 = time.perf_counter()
        numpy_peer(y, boxes)
        samples.append(time.perf_counter() - t0)
    t_numpy = median(samples)
    rows.append(["NumPy peer (integral image + eq. 20 only)", "-", n, f"{t_numpy * 1e3:.2f}",
                 f"{1 / t_numpy:.0f}"])
    print(f"Multi-Bernoulli step at 768 x 576, median over {args.frames} frames, one thread\n")
    print_table(["configuration", "tracks", "particles", "ms / frame", "frames / s"], rows)
    print(f"\nNumPy peer / vtrack defaults: {t_numpy / t_vtrack:.1f}x; "
          f"vtrack uses {t_vtrack / 0.020:.0%} of the 20 ms end-to-end budget.")


if __name__ == "__main__":
    main()

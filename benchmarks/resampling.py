"""Systematic resampling throughput: vtrack vs a vectorised NumPy version vs FilterPy.

Usage: python benchmarks/resampling.py [--repeats R]
All three run single-threaded on the same normalised weights; the table gives median time per
call, throughput in million particles per second, and each peer's time divided by vtrack's.
"""

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _table import median_seconds, print_table  # noqa: E402

import vtrack  # noqa: E402

try:
    from filterpy.monte_carlo import systematic_resample as filterpy_systematic
except ImportError:  # optional peer (requirements/bench.txt)
    filterpy_systematic = None


def numpy_systematic(weights, rng):
    """The usual vectorised NumPy implementation: cumsum + searchsorted, O(N log N)."""
    n = len(weights)
    positions = (rng.random() + np.arange(n)) / n
    cumulative = np.cumsum(weights)
    cumulative[-1] = 1.0  # guard against round-off
    return np.searchsorted(cumulative, positions, side="right")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()

    header = ["N", "vtrack (ms)", "vtrack (M/s)", "NumPy (ms)", "NumPy / vtrack"]
    if filterpy_systematic is not None:
        header += ["FilterPy (ms)", "FilterPy / vtrack"]
    rows = []
    for n in (10**3, 10**4, 10**5, 10**6):
        weights = np.random.default_rng(n).random(n)
        weights /= weights.sum()
        vt_rng = vtrack.Rng(1)
        np_rng = np.random.default_rng(1)
        t_vtrack = median_seconds(lambda: vtrack.smc.resample(weights, vt_rng), args.repeats)
        t_numpy = median_seconds(lambda: numpy_systematic(weights, np_rng), args.repeats)
        row = [f"{n:,}", f"{t_vtrack * 1e3:.3f}", f"{n / t_vtrack / 1e6:.0f}",
               f"{t_numpy * 1e3:.3f}", f"{t_numpy / t_vtrack:.1f}x"]
        if filterpy_systematic is not None:
            np.random.seed(1)
            t_fp = median_seconds(lambda: filterpy_systematic(weights), args.repeats)
            row += [f"{t_fp * 1e3:.3f}", f"{t_fp / t_vtrack:.1f}x"]
        rows.append(row)
    print("Systematic resampling, N draws from N weights, median per call, one thread\n")
    print_table(header, rows)
    if filterpy_systematic is None:
        print("\nFilterPy not installed (pip install -r requirements/bench.txt); its column is skipped.")


if __name__ == "__main__":
    main()

"""Helpers shared by the benchmark scripts: median timing and markdown tables."""

import time
from statistics import median


def median_seconds(fn, repeats=15, min_time=0.02):
    """Median wall time of one call of `fn`, each sample looping enough calls to last `min_time`."""
    fn()  # warm-up
    start = time.perf_counter()
    fn()
    once = max(time.perf_counter() - start, 1e-9)
    loops = max(1, int(min_time / once))
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(loops):
            fn()
        samples.append((time.perf_counter() - start) / loops)
    return median(samples)


def print_table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---" for _ in header) + "|")
    for row in rows:
        print("| " + " | ".join(str(cell) for cell in row) + " |")

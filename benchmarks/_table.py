"""Helpers shared by the benchmark scripts: median timing and markdown tables."""

import time
from statistics import median


def median_seconds(fn, repeats=15, min_time=0.02, clock=time.perf_counter):
    """Median time of one call of `fn`, each sample looping enough calls to last `min_time`.
    `clock`: wall time by default; time.thread_time gives the calling thread's CPU time, robust
    when other jobs share the cores (for single-threaded code)."""
    fn()  # warm-up
    start = clock()
    fn()
    once = max(clock() - start, 1e-9)
    loops = max(1, int(min_time / once))
    samples = []
    for _ in range(repeats):
        start = clock()
        for _ in range(loops):
            fn()
        samples.append((clock() - start) / loops)
    return median(samples)


def print_table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---" for _ in header) + "|")
    for row in rows:
        print("| " + " | ".join(str(cell) for cell in row) + " |")

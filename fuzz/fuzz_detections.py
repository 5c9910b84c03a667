"""Fuzz the MOTChallenge detection-file reader (vtrack.io.read_detections, the reader behind `vtrack
track --detections`) and, on what it accepts, the box tracker (vtrack.track_detections).

Inputs are raw bytes (libFuzzer mutates the seed files of fuzz/corpus/detections/) and, for
inputs whose first byte is 0xF0 or above, lines assembled from the fuzz data out of the tokens a
det file is made of, so that numbers, separators and edge values (huge frames, NaN, exponents,
stray bytes) meet the parser far more often than random bytes would.

    .venv/bin/python fuzz/fuzz_detections.py -max_total_time=60 fuzz/corpus/detections
"""

from __future__ import annotations

import sys

import atheris

# Coverage feedback from vtrack's Python code only: the compiled module is not instrumented, and
# instrumenting NumPy and OpenCV's Python parts took ~20 s per harness start for nothing.
with atheris.instrument_imports(include=["vtrack"]):
    import numpy as np
    import vtrack

from _common import check, scratch_file

TOKENS = [b"1", b"2", b"0", b"-1", b"7", b"100000000000000", b"1e15", b"1e16", b"1e308", b"-0",
          b"nan", b"inf", b"-inf", b"0x10", b"1.5", b"2.", b".5", b"1e-320", b"  3 ", b"",
          b"\xff", b"\x00", b"\t", b"\r", b"99999999999999999999", b"4294967296", b"-2147483649",
          b"5e-1", b"+4", b"1_0", b"\xc3\xa9"]


def structured(fdp: atheris.FuzzedDataProvider) -> bytes:
    lines = []
    for _ in range(fdp.ConsumeIntInRange(0, 12)):
        fields = [TOKENS[fdp.ConsumeIntInRange(0, len(TOKENS) - 1)]
                  if fdp.ConsumeBool() else str(fdp.ConsumeRegularFloat()).encode()
                  for _ in range(fdp.ConsumeIntInRange(0, 12))]
        sep = b"," if fdp.ConsumeIntInRange(0, 9) else b";"
        lines.append(sep.join(fields))
    return b"\n".join(lines) + (b"\n" if fdp.ConsumeBool() else b"")


def one_input(data: bytes) -> None:
    # A first byte >= 0xF0 asks for an assembled file; anything else is the file itself (so the
    # seed files are plain files, mutated by libFuzzer).
    text = structured(atheris.FuzzedDataProvider(data[1:])) if data[:1] >= b"\xf0" else data
    with scratch_file(text, ".txt") as path:
        rows = None

        def read():
            nonlocal rows
            rows = vtrack.io.read_detections(path, min_confidence=-np.inf)

        check(read)
        if rows is not None and 0 < len(rows) <= 64:
            check(lambda: vtrack.track_detections(rows, hypothesis_budget=20))
        check(lambda: vtrack.io.read_mot(path))


def main() -> None:
    atheris.Setup(sys.argv, one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()

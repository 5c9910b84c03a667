"""MOTChallenge text files: ``frame,id,x,y,w,h,conf,x3d,y3d,z3d`` per line, frames 1-based.

:func:`write_mot` writes atomically (a temporary file in the same folder, renamed over the
target), so an interrupted run never leaves a half-written file. :func:`read_mot` returns an
``(N, 10)`` float64 array and raises ``ValueError`` naming the file and line of a malformed row.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable, Sequence, Union

import numpy as np

from ._files import atomic_open

PathLike = Union[str, "os.PathLike[str]"]

COLUMNS = ("frame", "id", "x", "y", "w", "h", "conf", "x3d", "y3d", "z3d")


def track_rows(frame: int, tracks: Iterable) -> list:
    """MOT rows ``(frame, id, x, y, w, h, conf, -1, -1, -1)`` for the tracks of one frame.

    `tracks` are objects with ``label``, ``x``, ``y``, ``w``, ``h`` and ``existence`` (as
    returned by :meth:`vtrack.MultiBernoulliTracker.step`); the existence probability is written
    as the confidence. `frame` is 1-based, as MOTChallenge counts.
    """
    if frame < 1:
        raise ValueError(f"frame must be >= 1 (MOTChallenge frames are 1-based), got {frame}")
    return [(frame, t.label, t.x, t.y, t.w, t.h, t.existence, -1, -1, -1) for t in tracks]


def write_mot(path: PathLike, rows: Union[np.ndarray, Sequence[Sequence[float]]]) -> None:
    """Write rows of at least 7 columns (frame, id, x, y, w, h, conf[, x3d, y3d, z3d]).

    Missing 3-D columns are written as -1. Frame and id are written as integers, the box with
    two decimals and conf with four, as the C++ writer behind ``vtrack track`` does, so the same
    rows give the same bytes from Python and from the CLI.
    """
    arr = np.asarray(rows, dtype=np.float64)
    if arr.size == 0:
        arr = arr.reshape(0, 10)
    if arr.ndim != 2 or not 7 <= arr.shape[1] <= 10:
        raise ValueError(f"rows must be a table of 7 to 10 columns, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError("rows contain NaN or infinite values")
    if arr.shape[1] < 10:
        arr = np.hstack([arr, -np.ones((arr.shape[0], 10 - arr.shape[1]))])
    with atomic_open(path) as f:
        for r in arr:
            f.write(f"{int(r[0])},{int(r[1])},{r[2]:.2f},{r[3]:.2f},{r[4]:.2f},{r[5]:.2f},"
                    f"{r[6]:.4f},{r[7]:g},{r[8]:g},{r[9]:g}\n")


def read_mot(path: PathLike) -> np.ndarray:
    """Read a MOTChallenge text file into an ``(N, 10)`` float64 array (blank lines skipped).

    Rows with 6 to 10 comma-separated numbers are accepted (missing columns become 1 for conf and
    -1 for the 3-D ones); anything else is a ``ValueError`` naming the file and line.
    """
    path = Path(path)
    rows = []
    with open(path) as f:
        for number, line in enumerate(f, start=1):
            line = line.strip()
            if not line:
                continue
            fields = [s.strip() for s in line.split(",")]
            if not 6 <= len(fields) <= 10:
                raise ValueError(f"{path}:{number}: expected 6 to 10 comma-separated values, "
                                 f"got {len(fields)}: {line!r}")
            try:
                values = [float(s) for s in fields]
            except ValueError:
                raise ValueError(f"{path}:{number}: not a number in {line!r}") from None
            if not all(np.isfinite(values)):
                raise ValueError(f"{path}:{number}: NaN or infinite value in {line!r}")
            if values[0] < 1 or values[0] != int(values[0]):
                raise ValueError(f"{path}:{number}: frame must be an integer >= 1, got {fields[0]}")
            if values[1] != int(values[1]):
                raise ValueError(f"{path}:{number}: id must be an integer, got {fields[1]}")
            defaults = [1.0, -1.0, -1.0, -1.0]
            rows.append(values + defaults[len(values) - 6:])
    return np.asarray(rows, dtype=np.float64).reshape(-1, 10)

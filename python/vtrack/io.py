"""Files vtrack reads and writes (the I/O of the C++ ``apps`` layer).

- MOTChallenge text, ``frame,id,x,y,w,h,conf,x3d,y3d,z3d`` per line, frames 1-based:
  :func:`mot_rows` turns any tracker's :class:`vtrack.Tracks` into rows, :func:`write_mot` writes
  them (the CLI's writer: through a temporary file renamed when complete, so an interrupted run
  never leaves a half-written file), :func:`read_mot` reads a tracks or ground-truth file into an
  ``(N, 10)`` float64 array (``ValueError`` naming the file and line of a malformed row), and
  :func:`read_detections` reads a detection file as ``vtrack track --detections`` does.
- Configuration files (YAML or JSON): :func:`load_config` returns the sections the CLI reads.
- Video: :func:`probe_video` decodes a video file or image folder and reports its frame count.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Union

import numpy as np

from ._core import VideoInfo, load_config, mot_rows, probe_video, read_detections, write_mot

PathLike = Union[str, "os.PathLike[str]"]

COLUMNS = ("frame", "id", "x", "y", "w", "h", "conf", "x3d", "y3d", "z3d")

__all__ = [
    "COLUMNS",
    "VideoInfo",
    "load_config",
    "mot_rows",
    "probe_video",
    "read_detections",
    "read_mot",
    "write_mot",
]


def read_mot(path: PathLike) -> np.ndarray:
    """Read a MOTChallenge text file into an ``(N, 10)`` float64 array (blank lines skipped).

    Rows with 6 to 10 comma-separated numbers are accepted (missing columns become 1 for conf and
    -1 for the 3-D ones); anything else is a ``ValueError`` naming the file and line.
    """
    path = Path(path)
    rows = []
    # Bytes that are not UTF-8 stay readable (as surrogates) so that the row that holds them is
    # reported with its file and line instead of a bare UnicodeDecodeError.
    with open(path, encoding="utf-8", errors="surrogateescape") as f:
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

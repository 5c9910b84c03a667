"""Atomic file writes: a file's final name only ever holds a complete file.

The content goes to a hidden temporary file in the same folder (``.NAME.XXXXXX.tmp``), which is
renamed over the target once it is closed; any failure (or KeyboardInterrupt) removes it. A
process killed mid-write (SIGKILL) can leave such a temporary file behind, never a half-written
target.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path
from typing import IO, Iterator, Union

PathLike = Union[str, "os.PathLike[str]"]


def _umask() -> int:
    # Linux reports it without changing it; os.umask() sets it (briefly, for every thread).
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_open(path: PathLike, mode: str = "w", **kwargs) -> Iterator[IO]:
    """``open(path, mode)`` whose content appears at `path` only when the block completes.

    The file gets the permissions ``open`` would give it (0666 less the umask), not mkstemp's
    0600.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, mode, **kwargs) as f:
            yield f
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def is_temporary(name: str) -> bool:
    """Whether a file name is one of :func:`atomic_open`'s temporary names."""
    return name.startswith(".") and name.endswith(".tmp")

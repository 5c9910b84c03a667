"""What every vtrack fuzz harness shares: the contract it checks and scratch files.

The contract (issue 16): whatever bytes, arrays or parameters come in, a public entry point
returns normally or raises TypeError, ValueError or OSError (vtrack.InvalidType,
vtrack.InvalidArgument, vtrack.IoError derive from them). Anything else -- a crash, a hang (the
fuzzer's -timeout), RuntimeError, SystemError, MemoryError, UnicodeDecodeError hiding a message
-- is a finding, and every finding becomes a regression test (a corpus file under
fuzz/corpus/<harness>/ replayed by tests/test_fuzz_corpus.py, and a test of its own).
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from typing import Callable, Iterator

ALLOWED = (TypeError, ValueError, OSError)
# Subclasses of the allowed errors that still mean something went wrong: a message that could not
# be decoded hides the file:line it was meant to give.
FORBIDDEN = (UnicodeError,)

SCRATCH = tempfile.mkdtemp(prefix="vtrack-fuzz-")


def check(call: Callable[[], object]) -> None:
    """Run `call`; return if it returns or raises an allowed error, re-raise anything else.

    MemoryError is allowed when it says what could not be allocated (vtrack's "cannot allocate
    n = ... samples ...", NumPy's "Unable to allocate ..."), never a bare std::bad_alloc.
    """
    try:
        call()
    except FORBIDDEN:
        raise
    except ALLOWED:
        pass
    except MemoryError as e:
        if not str(e).startswith(("cannot allocate", "Unable to allocate")):
            raise


@contextmanager
def scratch_file(data: bytes, suffix: str) -> Iterator[str]:
    """`data` in a file with `suffix` in the harness's scratch folder, removed afterwards."""
    fd, path = tempfile.mkstemp(suffix=suffix, dir=SCRATCH)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        yield path
    finally:
        os.unlink(path)


def corpus_dir(name: str) -> str:
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", name)

"""Shared pytest fixtures: the sample video (PETS2009 S2.L1, vtest.avi) and the vtrack executable."""

import os
import sysconfig
from pathlib import Path

import pytest


def _video_path() -> Path:
    return Path(os.environ.get("VTRACK_VIDEO", Path.home() / ".cache" / "vtrack" / "vtest.avi"))


@pytest.fixture(scope="session")
def video_path() -> Path:
    """vtest.avi: $VTRACK_VIDEO, else ~/.cache/vtrack/vtest.avi (`make test` fetches it)."""
    path = _video_path()
    if not path.is_file():
        pytest.fail(f"sample video not found at {path}: run `make test` (which fetches it) "
                    "or set VTRACK_VIDEO")
    return path


@pytest.fixture(scope="session")
def vtrack_exe() -> Path:
    """The `vtrack` executable installed next to this Python (in .venv/bin)."""
    exe = Path(sysconfig.get_path("scripts")) / "vtrack"
    if not exe.is_file():
        pytest.fail(f"vtrack executable not found at {exe}: install vtrack (`make build`)")
    return exe

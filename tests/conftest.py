"""Shared fixtures: the installed `vtrack` executable, the sample video, small synthetic videos."""

import os
import subprocess
import sysconfig
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[1]


def _vtrack_executable() -> Path:
    # The wheel installs the CLI into the environment's scripts folder (.venv/bin).
    return Path(sysconfig.get_path("scripts")) / "vtrack"


@pytest.fixture(scope="session")
def vtrack_cli():
    exe = _vtrack_executable()
    if not exe.exists():
        pytest.fail(f"vtrack executable not installed at {exe} (run `make build`)")

    def run(*args):
        return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True,
                              timeout=300)

    return run


@pytest.fixture(scope="session")
def sample_video() -> Path:
    """PETS2009 S2.L1 (vtest.avi), fetched by the Makefile into ~/.cache/vtrack."""
    path = Path(os.environ.get("VTRACK_VIDEO", Path.home() / ".cache" / "vtrack" / "vtest.avi"))
    if not path.exists():
        pytest.fail(f"sample video missing at {path}: `make test` fetches it")
    return path


@pytest.fixture
def write_video(tmp_path):
    """Writes `frames` (list of H x W x 3 uint8) as an MJPG .avi and returns its path."""
    cv2 = pytest.importorskip("cv2")

    def write(frames, name="clip.avi", fps=12.0):
        path = tmp_path / name
        h, w = frames[0].shape[:2]
        writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), fps, (w, h))
        assert writer.isOpened()
        for f in frames:
            writer.write(f)
        writer.release()
        return path

    return write


@pytest.fixture(scope="session")
def crossing_scenes(tmp_path_factory):
    """{seed: (scene, path)}: two seeded 320 x 240 scenes of 3 people crossing (vtrack.synthetic),
    150 frames, written as MJPG videos. Illumination drifts by 2 % (the KDE's stack spans 100
    frames). The foreground trackers' end-to-end tests run on them."""
    cv2 = pytest.importorskip("cv2")
    from vtrack.synthetic import make_scene  # noqa: PLC0415

    out = {}
    for seed in (3, 4):
        scene = make_scene(320, 240, n_frames=150, n_people=3, seed=seed,
                           illumination_amplitude=0.02)
        path = tmp_path_factory.mktemp(f"scene{seed}") / "scene.avi"
        writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 10.0, (320, 240))
        for k in range(len(scene)):
            writer.write(scene.frame(k))
        writer.release()
        out[seed] = (scene, path)
    return out


def random_frames(count, height=48, width=64, seed=0):
    rng = np.random.default_rng(seed)
    return [rng.integers(0, 256, (height, width, 3), dtype=np.uint8) for _ in range(count)]


DATA = REPO / "data"


@pytest.fixture(scope="session")
def glmb_standard_dir() -> Path:
    """The standard GLMB scenario shipped in data/glmb-standard (model, truth, ten fixed draws)."""
    path = DATA / "glmb-standard"
    if not (path / "truth.csv").exists():
        pytest.fail(f"GLMB standard data missing at {path}: it ships with the repository")
    return path


@pytest.fixture(scope="session")
def pets09_gt() -> Path:
    """PETS09-S2L1's MOT15 ground truth, shipped in data/pets09-s2l1/gt.txt."""
    path = DATA / "pets09-s2l1" / "gt.txt"
    if not path.exists():
        pytest.fail(f"PETS09-S2L1 ground truth missing at {path}: it ships with the repository")
    return path

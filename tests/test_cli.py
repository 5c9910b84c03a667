"""The `vtrack` executable: help, version, info, and its errors."""

import pytest

import vtrack
from conftest import random_frames


def test_help_and_version(vtrack_cli):
    result = vtrack_cli("--help")
    assert result.returncode == 0 and "info" in result.stdout
    result = vtrack_cli("--version")
    assert result.returncode == 0 and result.stdout.strip() == f"vtrack {vtrack.__version__}"
    result = vtrack_cli("info", "--help")
    assert result.returncode == 0 and "VIDEO_OR_IMAGE_FOLDER" in result.stdout


def test_info_on_the_sample_video(vtrack_cli, sample_video):
    result = vtrack_cli("info", sample_video)
    assert result.returncode == 0, result.stderr
    lines = dict(line.split(": ", 1) for line in result.stdout.strip().splitlines())
    assert lines["frames"] == "795"          # PETS2009 S2.L1 View 001
    assert lines["size"] == "768x576"
    assert float(lines["fps"]) == 10.0        # what the AVI header says (SOURCE.md)
    info = vtrack.io.probe_video(sample_video)
    assert (info.frame_count, info.width, info.height) == (795, 768, 576)


def test_info_on_a_written_video_and_an_image_folder(vtrack_cli, write_video, tmp_path):
    cv2 = __import__("cv2")
    path = write_video(random_frames(9))
    result = vtrack_cli("info", path)
    assert result.returncode == 0, result.stderr
    assert "frames: 9\n" in result.stdout and "size: 64x48\n" in result.stdout
    folder = tmp_path / "frames"
    folder.mkdir()
    for i, frame in enumerate(random_frames(4, seed=1)):
        cv2.imwrite(str(folder / f"{i:04d}.png"), frame)
    result = vtrack_cli("info", folder)
    assert result.returncode == 0, result.stderr
    assert "frames: 4\n" in result.stdout and "fps: unknown" in result.stdout


def test_errors_are_reported_not_crashed(vtrack_cli, write_video, tmp_path):
    cases = {
        (): 2,
        ("bogus",): 2,
        ("info",): 2,
        ("info", "a", "b"): 2,
        ("info", tmp_path / "missing.avi"): 1,
        ("info", tmp_path): 1,  # a folder with no images
    }
    not_video = tmp_path / "notes.avi"
    not_video.write_text("not a video\n")
    cases[("info", not_video)] = 1
    truncated = write_video(random_frames(40), name="truncated.avi")
    data = truncated.read_bytes()
    truncated.write_bytes(data[: len(data) // 2])
    cases[("info", truncated)] = 1
    for args, status in cases.items():
        result = vtrack_cli(*args)
        assert result.returncode == status, (args, result.stderr)
        assert result.stderr.startswith("vtrack: error: "), (args, result.stderr)
        assert result.stdout == ""
    assert "frame" in vtrack_cli("info", truncated).stderr  # names where decoding failed


def test_python_probe_video_errors(tmp_path):
    with pytest.raises(OSError, match="no such file"):
        vtrack.io.probe_video(tmp_path / "missing.avi")
    with pytest.raises(vtrack.IoError):
        vtrack.io.probe_video(tmp_path)

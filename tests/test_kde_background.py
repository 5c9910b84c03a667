"""vtrack.KdeBackground against the NumPy float64 transcription of eq. (10) (vtrack.reference),
on real frames of vtest.avi and on random images; the sample schedule frame by frame; closing,
freeze/reset, masks; bad input; and the `vtrack bgs` command line."""

import cv2
import numpy as np
import pytest

import vtrack
from vtrack.reference import KdeBackgroundReference, rgi_float64

TOLERANCE = 1e-3  # the agreement bar


@pytest.fixture(scope="module")
def video_frames(sample_video):
    """The first 36 frames of vtest.avi, decoded once."""
    cap = cv2.VideoCapture(str(sample_video))
    frames = []
    while len(frames) < 36:
        ok, frame = cap.read()
        assert ok, f"cannot decode frame {len(frames)} of {sample_video}"
        frames.append(frame)
    return frames


def expected_schedule(k, n_samples, period):
    """Section 3.1: samples at K0*floor(k/K0), K0*(floor(k/K0)-1), ..., at most N0 of them, >= 0."""
    newest = period * (k // period)
    return [t for t in range(newest - (n_samples - 1) * period, newest + 1, period) if t >= 0]


# ---- eq. (10) ------------------------------------------------------------------------------------

def test_reference_rgi_matches_bgr_to_rgi():
    # The reference's rgI is the documented conversion of vtrack.image.bgr_to_rgi (independent check
    # that the two agree on conventions: I = S/765, black -> r = g = 1/3).
    frame = np.random.default_rng(0).integers(0, 256, (9, 11, 3), dtype=np.uint8)
    frame[0, 0] = 0
    np.testing.assert_allclose(vtrack.image.bgr_to_rgi(frame), rgi_float64(frame), atol=1e-6)


@pytest.mark.parametrize("n_samples,period", [(4, 3), (10, 2)])
def test_matches_numpy_transcription_on_video_frame_by_frame(video_frames, n_samples, period):
    # update_threshold=0: the paper's stack (every K0-th frame whole), which the reference follows.
    model = vtrack.KdeBackground(n_samples=n_samples, period=period, closing=0, update_threshold=0)
    ref = KdeBackgroundReference(n_samples, period, model.params["bandwidth"])
    frames = video_frames if n_samples == 4 else video_frames[:24]
    for k, frame in enumerate(frames):
        y = model.apply(frame)
        y_ref = ref.apply(frame)
        assert model.sample_frames == expected_schedule(k, n_samples, period) == ref.sample_frames
        assert y.dtype == np.float32 and y.shape == frame.shape[:2]
        err = np.abs(y - y_ref).max()
        assert err < TOLERANCE, f"frame {k}: max |y - y_ref| = {err}"
    # The video is not trivially all-background: the comparison covers foreground too.
    assert (y_ref < 0.5).mean() > 0.001


@pytest.mark.parametrize("bandwidth", [(0.02, 0.02, 0.06), (0.005, 0.01, 0.02), (0.3, 0.2, 0.5)])
def test_matches_numpy_transcription_on_random_images(bandwidth):
    rng = np.random.default_rng(42)
    base = rng.integers(0, 256, (31, 45, 3), dtype=np.uint8)
    base[:4, :4] = 0  # black pixels
    model = vtrack.KdeBackground(n_samples=3, period=2, bandwidth=bandwidth, closing=0,
                                 update_threshold=0)
    ref = KdeBackgroundReference(3, 2, bandwidth)
    for k in range(9):
        noise = rng.integers(-15, 16, base.shape)
        frame = np.clip(base.astype(int) + noise, 0, 255).astype(np.uint8)
        frame[5:12, 5:20] = rng.integers(0, 256, (7, 15, 3))  # a "foreground" patch
        err = np.abs(model.apply(frame) - ref.apply(frame)).max()
        assert err < TOLERANCE, f"frame {k}: {err}"


def test_threads_and_memory_layout_do_not_change_the_result(video_frames):
    single = vtrack.KdeBackground(period=1, threads=1)
    pooled = vtrack.KdeBackground(period=1, threads=0)
    for frame in video_frames[:5]:
        flipped = frame[:, ::-1]  # a non-contiguous view
        np.testing.assert_array_equal(single.apply(flipped), pooled.apply(np.ascontiguousarray(flipped)))


def test_read_only_frames_are_accepted():
    rng = np.random.default_rng(1)
    a, b = vtrack.KdeBackground(period=1, closing=0), vtrack.KdeBackground(period=1, closing=0)
    for _ in range(3):
        frame = rng.integers(0, 256, (6, 7, 3), dtype=np.uint8)
        frozen = frame.copy()
        frozen.flags.writeable = False
        y = a.apply(frozen)
        np.testing.assert_array_equal(y, b.apply(frame))
    assert y.min() < 0.5  # random frames: not a trivial all-background comparison


# ---- closing, freeze/resume/reset, mask --------------------------------------------------------

def test_closing_is_morphological_closing_of_y(video_frames):
    # The paper's stack, so both hold the same samples (the selective update reads the closed y).
    plain = vtrack.KdeBackground(period=2, closing=0, update_threshold=0)
    closed = vtrack.KdeBackground(period=2, closing=5, update_threshold=0)
    for frame in video_frames[:12]:
        y_plain, y_closed = plain.apply(frame), closed.apply(frame)
    expected = cv2.morphologyEx(y_plain, cv2.MORPH_CLOSE, np.ones((5, 5), np.uint8))
    np.testing.assert_array_equal(y_closed, expected)
    np.testing.assert_array_equal(vtrack.image.close_square(y_plain, 5), expected)
    assert (y_closed >= y_plain).all()  # closing is extensive
    assert (y_closed < 0.5).sum() < (y_plain < 0.5).sum()  # it removed foreground specks


def test_freeze_resume_reset():
    model = vtrack.KdeBackground(n_samples=2, period=3, closing=0)
    grey = np.full((4, 5, 3), 90, np.uint8)
    red = grey.copy()
    red[..., 2] = 250
    for _ in range(4):
        model.apply(grey)  # samples at 0 and 3
    model.freeze()
    assert not model.learning
    for _ in range(5):
        y = model.apply(red)  # frames 4..8: 6 would be a sample time
    assert model.sample_frames == [0, 3]
    assert y.max() < 1e-3  # still judged against the grey background
    model.resume()
    model.apply(red)  # frame 9: sampled, replaces frame 0
    assert model.sample_frames == [3, 9]
    model.reset()
    assert model.frame_index == 0 and model.sample_frames == [] and model.learning
    y = model.apply(np.zeros((7, 3, 3), np.uint8))  # any size after a reset
    assert y.shape == (7, 3) and (y == 1).all()


def test_foreground_mask():
    y = np.array([[0.0, 0.2, 0.5], [0.7, 1.0, 0.49]], np.float32)
    mask = vtrack.image.foreground_mask(y, threshold=0.5)
    assert mask.dtype == np.uint8
    np.testing.assert_array_equal(mask, np.where(y < 0.5, 255, 0))
    with pytest.raises(ValueError, match="threshold"):
        vtrack.image.foreground_mask(y, threshold=1.5)
    with pytest.raises(TypeError, match="y"):
        vtrack.image.foreground_mask(y.astype(np.float64), threshold=0.5)


# ---- bad input -----------------------------------------------------------------------------------

def test_bad_frames():
    model = vtrack.KdeBackground()
    with pytest.raises(ValueError, match="frame"):
        model.apply(np.zeros((0, 5, 3), np.uint8))
    with pytest.raises(ValueError, match=r"frame must have shape \(H, W, 3\)"):
        model.apply(np.zeros((4, 5, 4), np.uint8))
    with pytest.raises(ValueError, match="frame"):
        model.apply(np.zeros((4, 5), np.uint8))
    with pytest.raises(TypeError, match="frame must have dtype uint8"):
        model.apply(np.zeros((4, 5, 3), np.float32))
    model.apply(np.zeros((4, 5, 3), np.uint8))
    with pytest.raises(vtrack.InvalidArgument, match=r"frame 1 is 5x6.*5x4"):
        model.apply(np.zeros((6, 5, 3), np.uint8))
    assert model.frame_index == 1


@pytest.mark.parametrize("kwargs,error,match", [
    (dict(n_samples=0), ValueError, "n_samples"),
    (dict(n_samples=-1), ValueError, "n_samples"),
    (dict(period=0), ValueError, "period"),
    (dict(bandwidth=(0.02, 0.0, 0.1)), ValueError, "sigma_g"),
    (dict(bandwidth=(-1, 0.02, 0.1)), ValueError, "sigma_r"),
    (dict(bandwidth=(0.02, 0.02, float("nan"))), ValueError, "bandwidth"),
    (dict(bandwidth=(0.02, 0.02)), ValueError, "bandwidth must hold 3 numbers"),
    (dict(bandwidth="wide"), TypeError, "bandwidth"),
    (dict(closing=2), ValueError, "closing"),
    (dict(threads=-2), ValueError, "threads"),
    (dict(update_threshold=1.5), ValueError, "update_threshold"),
    (dict(update_max_skips=0), ValueError, "update_max_skips"),
])
def test_bad_parameters(kwargs, error, match):
    with pytest.raises(error, match=match):
        vtrack.KdeBackground(**kwargs)


# ---- command line --------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def small_frames(video_frames):
    """Frames of vtest.avi at a quarter size, as PNG images (lossless input for the CLI)."""
    return [cv2.resize(f, (192, 144), interpolation=cv2.INTER_AREA) for f in video_frames[:20]]


def test_cli_writes_the_y_images_of_the_python_api(vtrack_cli, small_frames, tmp_path):
    folder = tmp_path / "frames"
    folder.mkdir()
    for i, f in enumerate(small_frames):
        cv2.imwrite(str(folder / f"{i:04d}.png"), f)
    out = tmp_path / "y"
    config = tmp_path / "bgs.yml"
    config.write_text("background: {n_samples: 4, period: 3, bandwidth: [0.03, 0.02, 0.08]}\n")
    proc = vtrack_cli("bgs", folder, "--out", out, "--config", config, "--set", "closing=3",
                      "--set", "threads=1")
    assert proc.returncode == 0, proc.stderr
    assert "bgs: frame 20/20" in proc.stderr
    assert proc.stdout.strip() == f"wrote 20 y images to {out} (PNG folder)"
    model = vtrack.KdeBackground(n_samples=4, period=3, bandwidth=(0.03, 0.02, 0.08), closing=3)
    names = sorted(p.name for p in out.iterdir())
    assert names == [f"{i:06d}.png" for i in range(20)]
    for i, f in enumerate(small_frames):
        expected = np.clip(np.rint(model.apply(f) * 255), 0, 255).astype(np.uint8)
        written = cv2.imread(str(out / f"{i:06d}.png"), cv2.IMREAD_UNCHANGED)
        assert written.dtype == np.uint8 and written.ndim == 2
        assert np.abs(written.astype(int) - expected).max() <= 1  # rounding of .5 cases


def test_cli_writes_a_video(vtrack_cli, write_video, small_frames, tmp_path):
    clip = write_video(small_frames)
    out = tmp_path / "y.mkv"
    proc = vtrack_cli("bgs", clip, "--out", out)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["clip.avi", "y.mkv"]  # no partial file
    cap = cv2.VideoCapture(str(out))
    count = 0
    while cap.read()[0]:
        count += 1
    assert count == len(small_frames)


def test_cli_truncated_video_names_the_frame_and_keeps_complete_images(vtrack_cli, write_video,
                                                                        small_frames, tmp_path):
    clip = write_video(small_frames)
    with open(clip, "r+b") as fh:
        fh.truncate(clip.stat().st_size // 2)
    out = tmp_path / "y"
    proc = vtrack_cli("bgs", clip, "--out", out)
    assert proc.returncode == 1
    assert proc.stdout == ""
    line = proc.stderr.strip().splitlines()[-1]
    assert line.startswith("vtrack: error: cannot decode frame ")
    bad = int(line.split("cannot decode frame ")[1].split()[0])
    assert 0 < bad < len(small_frames)
    names = sorted(p.name for p in out.iterdir())
    assert names == [f"{i:06d}.png" for i in range(bad)]
    for name in names:
        assert cv2.imread(str(out / name), cv2.IMREAD_UNCHANGED).shape == (144, 192)
    # Video output: nothing is left behind, neither the output nor a partial file.
    proc = vtrack_cli("bgs", clip, "--out", tmp_path / "y.avi")
    assert proc.returncode == 1 and f"frame {bad}" in proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["clip.avi", "y"]


@pytest.mark.parametrize("args,status,match", [
    (["--set", "n_samples=0"], 2, "n_samples"),
    (["--set", "period=-1"], 2, "period"),
    (["--set", "bandwidth=0.02,0,0.1"], 2, "sigma_g"),
    (["--set", "bandwidth=0.02,0.1"], 2, "bandwidth must be 3 numbers"),
    (["--set", "closing=x"], 2, "closing must be an integer"),
    (["--set", "threads=-1"], 2, "threads"),
    (["--set", "n_sample=3"], 2, "did you mean 'n_samples'"),
    (["--samples", "4"], 2, "unknown option '--samples'"),
    ([], 2, "--out"),
])
def test_cli_bad_arguments(vtrack_cli, sample_video, tmp_path, args, status, match):
    out = [] if not args else ["--out", tmp_path / "y"]
    proc = vtrack_cli("bgs", sample_video, *out, *args)
    assert proc.returncode == status
    assert proc.stderr.startswith("vtrack: error: ") and match in proc.stderr
    assert not (tmp_path / "y").exists()


def test_cli_missing_video(vtrack_cli, tmp_path):
    proc = vtrack_cli("bgs", tmp_path / "nope.avi", "--out", tmp_path / "y")
    assert proc.returncode == 1 and "nope.avi" in proc.stderr

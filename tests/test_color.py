"""Color histograms, Bhattacharyya coefficient, color likelihood and ColorModel (part-based
paper eqs. 9-11) against a NumPy transcription: OpenCV's HSV_FULL binned by floor(c * n / 256),
np.bincount over the box's pixels, Nummiaro's kernel written out, the closed forms."""

import math

import cv2
import numpy as np
import pytest

import vtrack


def frame_of(seed, h=48, w=64):
    rng = np.random.default_rng(seed)
    small = rng.integers(0, 256, (h // 8 + 1, w // 8 + 1, 3), dtype=np.uint8)
    frame = np.repeat(np.repeat(small, 8, axis=0), 8, axis=1)[:h, :w].copy()
    noise = rng.random((h, w, 3)) < 0.25
    frame[noise] = rng.integers(0, 256, int(noise.sum()), dtype=np.uint8)
    return frame


def numpy_bins(frame, bins):
    hsv = cv2.cvtColor(frame, cv2.COLOR_BGR2HSV_FULL).astype(np.int64)
    h, s, v = (hsv[..., i] * bins[i] // 256 for i in range(3))
    return (h * bins[1] + s) * bins[2] + v


def numpy_histogram(frame, box, bins=(16, 4, 4), kernel=False):
    x, y, w, h = box
    x0, x1 = math.floor(x + 0.5), math.floor(x + w + 0.5)
    y0, y1 = math.floor(y + 0.5), math.floor(y + h + 0.5)
    rows, cols = frame.shape[:2]
    x0, x1, y0, y1 = max(x0, 0), min(x1, cols), max(y0, 0), min(y1, rows)
    m = bins[0] * bins[1] * bins[2]
    if x1 <= x0 or y1 <= y0:
        return np.zeros(m)
    idx = numpy_bins(frame, bins)[y0:y1, x0:x1]
    weight = np.ones(idx.shape)
    if kernel:  # Nummiaro et al.: k(r) = 1 - r^2 / a^2, a^2 = (w/2)^2 + (h/2)^2
        dx = np.arange(x0, x1) + 0.5 - (x + w / 2)
        dy = np.arange(y0, y1) + 0.5 - (y + h / 2)
        weight = np.maximum(0, 1 - (dx[None, :] ** 2 + dy[:, None] ** 2) / ((w * w + h * h) / 4))
    hist = np.bincount(idx.ravel(), weight.ravel(), minlength=m)
    return hist / hist.sum() if hist.sum() > 0 else hist


def test_hsv_bins_of_pure_colors():
    # HSV_FULL hue codes: red 0, yellow 43, green 85, blue 171 -> bins 0, 2, 5, 10 of 16.
    px = np.array([[[0, 0, 255], [0, 255, 255], [0, 255, 0], [255, 0, 0], [128, 128, 128]]],
                  np.uint8)
    u = vtrack.image.hsv_bins(px)
    assert u.dtype == np.uint16 and u.shape == (1, 5)
    np.testing.assert_array_equal(u[0], [(h * 4 + 3) * 4 + 3 for h in (0, 2, 5, 10)] + [2])


@pytest.mark.parametrize("bins", [(16, 4, 4), (8, 3, 5), (1, 1, 2)])
def test_hsv_bins_match_numpy(bins):
    frame = frame_of(1)
    np.testing.assert_array_equal(vtrack.image.hsv_bins(frame, bins=bins), numpy_bins(frame, bins))


def test_hsv_bins_of_a_frame_agree_with_opencv_python():
    # vtrack computes OpenCV's integer HSV_FULL itself; cv2 (another OpenCV build) must agree.
    frame = frame_of(9, 300, 401)
    np.testing.assert_array_equal(vtrack.image.hsv_bins(frame), numpy_bins(frame, (16, 4, 4)))


@pytest.mark.parametrize("kernel", [False, True])
def test_histograms_match_numpy(kernel):
    frame = frame_of(2)
    rng = np.random.default_rng(3)
    for _ in range(40):
        box = (rng.uniform(-15, 70), rng.uniform(-15, 50), rng.uniform(0, 30), rng.uniform(0, 40))
        hist = vtrack.image.hsv_histogram(frame, box, kernel=kernel)
        assert hist.shape == (16, 4, 4)
        np.testing.assert_allclose(hist.ravel(), numpy_histogram(frame, box, kernel=kernel),
                                   atol=1e-12)
        assert hist.sum() == pytest.approx(1.0) or hist.sum() == 0.0


def test_bhattacharyya_closed_forms():
    assert vtrack.image.bhattacharyya_coefficient([1, 0], [0.5, 0.5]) == pytest.approx(math.sqrt(0.5))
    # Histograms of the same shape, whatever their scale.
    assert vtrack.image.bhattacharyya_coefficient([2, 6, 8], [1, 3, 4]) == pytest.approx(1.0)
    assert vtrack.image.bhattacharyya_coefficient([1, 0], [0, 1]) == 0.0
    p, q = np.random.default_rng(4).random((2, 4, 4, 4))
    expected = np.sum(np.sqrt(p / p.sum() * q / q.sum()))
    assert vtrack.image.bhattacharyya_coefficient(p, q) == pytest.approx(expected, rel=1e-14)
    assert vtrack.image.bhattacharyya_distance(p, q) == pytest.approx(math.sqrt(1 - expected), rel=1e-12)
    with pytest.raises(ValueError, match="same number of bins"):
        vtrack.image.bhattacharyya_coefficient([1, 2], [1, 2, 3])
    with pytest.raises(ValueError, match="p"):
        vtrack.image.bhattacharyya_coefficient([1, -1], [1, 1])
    with pytest.raises(ValueError, match="sum of q"):
        vtrack.image.bhattacharyya_coefficient([1, 1], [0, 0])
    with pytest.raises(TypeError):
        vtrack.image.bhattacharyya_coefficient(["a"], [1])


def test_color_log_likelihood_is_equation_11():
    rho = np.array([0.0, 0.5, 0.9, 1.0])
    for sigma in (0.2, math.sqrt(0.2)):
        p = np.exp(-(1 - rho) / (2 * sigma ** 2)) / math.sqrt(2 * math.pi * sigma ** 2)
        np.testing.assert_allclose(vtrack.image.color_log_likelihood(rho, sigma=sigma), np.log(p),
                                   rtol=1e-12)
    # The default is the text's sigma^2 = 0.2.
    assert vtrack.image.color_log_likelihood(0.7) == pytest.approx(
        vtrack.image.color_log_likelihood(0.7, sigma=math.sqrt(0.2)))
    assert isinstance(vtrack.image.color_log_likelihood(0.7), float)
    with pytest.raises(ValueError, match="sigma"):
        vtrack.image.color_log_likelihood(rho, sigma=0.0)


@pytest.mark.parametrize("method", ["auto", "direct", "incremental"])
def test_color_model_scores_match_numpy(method):
    frame = frame_of(5, 96, 128)
    box = (40.3, 20.6, 24.0, 50.0)
    model = vtrack.image.ColorModel(frame, box)
    q = numpy_histogram(frame, box)
    np.testing.assert_allclose(model.reference.ravel(), q, atol=1e-12)
    rng = np.random.default_rng(6)
    boxes = np.column_stack([40 + rng.normal(0, 4, 60), 20 + rng.normal(0, 4, 60),
                             24 + rng.normal(0, 2, 60), 50 + rng.normal(0, 3, 60)])
    boxes[:3] = [(500, 500, 10, 10), (-5, -5, 20, 20), (10, 10, 0, 5)]  # outside, clipped, empty
    rho = model.coefficients(frame, boxes, method=method)
    expected = [np.sum(np.sqrt(numpy_histogram(frame, b) * q)) for b in boxes]
    np.testing.assert_allclose(rho, expected, atol=2e-6)
    assert rho[0] == 0.0 and rho[2] == 0.0
    sigma = 0.2
    np.testing.assert_allclose(model.log_likelihood(frame, boxes, sigma=sigma),
                               vtrack.image.color_log_likelihood(rho, sigma=sigma), atol=1e-4)


def test_kernel_model_and_from_histogram():
    frame = frame_of(7, 96, 128)
    box = (30.0, 10.0, 30.0, 60.0)
    model = vtrack.image.ColorModel(frame, box, kernel=True, bins=(8, 4, 4))
    assert model.bins == (8, 4, 4) and model.kernel
    q = numpy_histogram(frame, box, bins=(8, 4, 4), kernel=True)
    boxes = np.array([box, (33.0, 12.0, 28.0, 61.0), (60.0, 30.0, 20.0, 40.0)])
    expected = [np.sum(np.sqrt(numpy_histogram(frame, b, bins=(8, 4, 4), kernel=True) * q))
                for b in boxes]
    np.testing.assert_allclose(model.coefficients(frame, boxes), expected, atol=1e-9)
    assert model.coefficients(frame, boxes)[0] == pytest.approx(1.0)
    for method in ("direct", "incremental"):  # per-pixel weights, per-bin moments
        np.testing.assert_allclose(model.coefficients(frame, boxes, method=method), expected,
                                   atol=1e-9)
    same = vtrack.image.ColorModel.from_histogram(model.reference * 7.0, kernel=True)
    np.testing.assert_allclose(same.reference, model.reference)


def test_bad_input():
    frame = frame_of(8)
    with pytest.raises(ValueError, match="no pixel"):
        vtrack.image.ColorModel(frame, (100, 100, 10, 10))
    with pytest.raises(ValueError, match="box"):
        vtrack.image.ColorModel(frame, (1, 2, 3))
    with pytest.raises(ValueError, match="NaN"):
        vtrack.image.ColorModel(frame, (1, 2, np.nan, 4))
    with pytest.raises(TypeError, match="frame"):
        vtrack.image.ColorModel(frame.astype(np.float32), (1, 2, 3, 4))
    with pytest.raises(ValueError, match="bins_s"):
        vtrack.image.hsv_histogram(frame, (0, 0, 5, 5), bins=(16, 0, 4))
    with pytest.raises(TypeError, match="bins"):
        vtrack.image.hsv_histogram(frame, (0, 0, 5, 5), bins=(16, 4.0, 4))
    with pytest.raises(ValueError, match="bins"):
        vtrack.image.hsv_histogram(frame, (0, 0, 5, 5), bins=(16, 4))
    model = vtrack.image.ColorModel(frame, (0, 0, 10, 10))
    with pytest.raises(ValueError, match=r"\(N, 4\)"):
        model.coefficients(frame, np.zeros((3, 5)))
    with pytest.raises(ValueError, match="method"):
        model.coefficients(frame, np.zeros((1, 4)), method="fast")
    assert model.coefficients(frame, np.zeros((0, 4))).shape == (0,)
    with pytest.raises(ValueError, match="template histogram sum"):
        vtrack.image.ColorModel.from_histogram(np.zeros((16, 4, 4)))

"""rgI conversion and integral images against NumPy transcriptions."""

import numpy as np
import pytest

import vtrack


def rgi_reference(bgr):
    """Eqs. 6-8 of the mb-tbd paper in float64, with I = (R+G+B)/765 and black -> r = g = 1/3."""
    b, g, r = (bgr[..., i].astype(np.float64) for i in range(3))
    s = r + g + b
    with np.errstate(invalid="ignore", divide="ignore"):
        rr = np.where(s > 0, r / s, 1 / 3)
        gg = np.where(s > 0, g / s, 1 / 3)
    return np.stack([rr, gg, s / 765.0], axis=-1)


def test_bgr_to_rgi_matches_equations():
    rng = np.random.default_rng(1)
    frame = rng.integers(0, 256, (37, 53, 3), dtype=np.uint8)
    frame[0, 0] = 0
    frame[1, 1] = 255
    out = vtrack.image.bgr_to_rgi(frame)
    assert out.dtype == np.float32 and out.shape == (37, 53, 3)
    np.testing.assert_allclose(out, rgi_reference(frame), atol=1e-6)
    # A non-contiguous view (every other column) gives the same as its contiguous copy.
    np.testing.assert_array_equal(vtrack.image.bgr_to_rgi(frame[:, ::2]),
                                  vtrack.image.bgr_to_rgi(np.ascontiguousarray(frame[:, ::2])))


@pytest.mark.parametrize(
    "frame, error, match",
    [
        (np.zeros((4, 4, 3), np.float32), TypeError, "uint8"),
        (np.zeros((4, 4), np.uint8), ValueError, r"\(H, W, 3\)"),
        (np.zeros((4, 4, 4), np.uint8), ValueError, r"\(H, W, 3\)"),
        (np.zeros((0, 4, 3), np.uint8), ValueError, "empty"),
    ],
)
def test_bgr_to_rgi_rejects_bad_frames(frame, error, match):
    with pytest.raises(error, match=match):
        vtrack.image.bgr_to_rgi(frame)


@pytest.mark.parametrize("dtype", [np.uint8, np.float32, np.float64])
def test_integral_image_matches_numpy_sums(dtype):
    rng = np.random.default_rng(2)
    image = (rng.random((41, 67)) * 200).astype(dtype)
    ii = vtrack.image.IntegralImage(image)
    assert ii.shape == (41, 67)
    rects = np.column_stack([
        rng.integers(-20, 87, 300), rng.integers(-20, 61, 300),
        rng.integers(-5, 80, 300), rng.integers(-5, 60, 300),
    ]).astype(np.int32)
    expected = []
    for x, y, w, h in rects:
        x0, y0 = max(x, 0), max(y, 0)
        x1, y1 = min(x + w, 67), min(y + h, 41)
        expected.append(image[y0:y1, x0:x1].astype(np.float64).sum() if x1 > x0 and y1 > y0 else 0.0)
    np.testing.assert_allclose(ii.sums(rects), expected, rtol=1e-12, atol=1e-9)
    x, y, w, h = rects[0]
    assert ii.sum(int(x), int(y), int(w), int(h)) == pytest.approx(expected[0], abs=1e-9)
    assert ii.area(60, 30, 20, 20) == 7 * 11


def test_integral_image_rejects_bad_images():
    with pytest.raises(TypeError, match="image"):
        vtrack.image.IntegralImage(np.zeros((3, 3), np.int16))
    with pytest.raises(ValueError, match="image"):
        vtrack.image.IntegralImage(np.zeros((3, 3, 3), np.float32))
    with pytest.raises(ValueError, match="rects"):
        vtrack.image.IntegralImage(np.zeros((3, 3), np.float32)).sums(np.zeros((2, 3)))

"""vtrack.models.ForegroundSizeEstimator (the multi-Bernoulli tracker's learnt person size)
against a NumPy transcription of its statistic (models/person_size.hpp), and on scenes whose
person height is known."""

import cv2
import numpy as np
import pytest

from vtrack.models import ForegroundSizeEstimator

H_BINS, A_BINS = 16, 8   # bins per octave of height and area


def log2_bin(v, per_octave, n):
    return int(np.clip(np.floor(np.log2(v) * per_octave), 0, n - 1))


def binned_median(hist, per_octave):
    total = hist.sum()
    if total <= 0:
        return 0.0
    cum = np.cumsum(hist)
    b = int(np.searchsorted(cum, 0.5 * total))          # first bin reaching half
    below = cum[b - 1] if b > 0 else 0.0
    return 2.0 ** ((b + (0.5 * total - below) / hist[b]) / per_octave)


def reference_height(images, aspect=0.35, min_area_fraction=1e-4):
    """The header's statistic, transcribed: components off the top and bottom borders, at least
    the area floor;
    count median over components at least a person a third as tall as the area-weighted median,
    then at least a person half as tall as that count median."""
    comps = []
    for y in images:
        mask = (y < 0.5).astype(np.uint8)
        _, _, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
        rows = y.shape[0]
        for _, y0, _, h, a in stats[1:]:
            if a < max(min_area_fraction * y.size, 1) or y0 == 0 or y0 + h == rows:
                continue
            comps.append((h, a))
    if not comps:
        return 0.0
    hb = np.array([log2_bin(h, H_BINS, 14 * H_BINS) for h, _ in comps])
    ab = np.array([log2_bin(a, A_BINS, 28 * A_BINS) for _, a in comps])
    area = np.array([a for _, a in comps], float)
    anchor = binned_median(np.bincount(hb, area, 14 * H_BINS), H_BINS)

    def count_median(min_area):
        keep = ab >= log2_bin(max(min_area, 1.0), A_BINS, 28 * A_BINS)
        return binned_median(np.bincount(hb[keep], minlength=14 * H_BINS).astype(float), H_BINS)

    first = count_median(aspect * (anchor / 3) ** 2)
    if first <= 0:
        return anchor
    second = count_median(aspect * (first / 2) ** 2)
    return second if second > 0 else first


def scene(rng, n_people, n_groups, height=90, size=(480, 360)):
    """y with n_people single people (height ~ N(height, 8%)), n_groups groups of two to four
    people merged side by side or one behind the other (placed apart from each other, a
    rectangle each), and noise specks."""
    y = np.ones(size[::-1], np.float32)
    taken = np.zeros(y.shape, bool)
    boxes = []
    for _ in range(n_people):
        h = int(height * rng.normal(1, 0.08))
        boxes.append((int(0.35 * h), h))
    for _ in range(n_groups):
        k = int(rng.integers(2, 5))
        boxes.append((int(0.35 * height * k * rng.uniform(0.5, 1)),
                      int(height * (1 + 0.4 * (k - 1) * rng.random()))))
    for w, h in boxes:
        for _ in range(100):   # a free place, two pixels clear of the others and the border
            x0 = int(rng.integers(2, max(3, size[0] - w - 2)))
            y0 = int(rng.integers(2, max(3, size[1] - h - 2)))
            if not taken[y0 - 2:y0 + h + 2, x0 - 2:x0 + w + 2].any():
                taken[y0 - 2:y0 + h + 2, x0 - 2:x0 + w + 2] = True
                y[y0:y0 + h, x0:x0 + w] = 0.1
                break
    specks = (rng.random(y.shape) < 0.002) & ~taken
    y[specks] = 0.2
    return y


def test_matches_the_numpy_transcription():
    rng = np.random.default_rng(4)
    for trial in range(5):
        images = [scene(rng, int(rng.integers(0, 5)), int(rng.integers(0, 3)),
                        height=float(rng.uniform(30, 120))) for _ in range(8)]
        est = ForegroundSizeEstimator()
        for y in images:
            est.observe(y)
        assert est.frames == len(images)
        assert est.person_height == pytest.approx(reference_height(images), rel=1e-9)


@pytest.mark.parametrize("height", [30, 90, 150])
def test_learns_the_person_height_among_groups(height):
    # Groups as numerous as 40 % of the single people, covering more area than they do: the
    # estimate is a single person's height (within the 8 % spread and a bin), where an
    # area-weighted median is pulled towards the groups.
    rng = np.random.default_rng(height)
    size = (int(6 * height), int(4 * height))
    est = ForegroundSizeEstimator()
    images = [scene(rng, 5, 2, height, size) for _ in range(30)]
    for y in images:
        est.observe(y)
    assert est.person_height == pytest.approx(height, rel=0.07)


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="half_life"):
        ForegroundSizeEstimator(half_life=0.0)
    with pytest.raises(ValueError, match="aspect"):
        ForegroundSizeEstimator(aspect=-1.0)
    est = ForegroundSizeEstimator()
    with pytest.raises(TypeError, match="float32"):
        est.observe(np.ones((10, 10), np.uint8))
    with pytest.raises((TypeError, ValueError), match="threshold"):
        est.observe(np.ones((10, 10), np.float32), threshold=float("nan"))
    est.observe(np.ones((10, 10), np.float32))   # no foreground: nothing learnt
    assert est.person_height == 0.0 and est.weight == 0.0


@pytest.mark.parametrize("scale", [1.0, 0.6, 0.4])
def test_person_height_line_holds_at_every_scale(scale):
    # A ground plane in perspective, h = 0.25 foot - 10 px at 640 x 480 (30 px at foot row 160,
    # 107 at 470), resized by `scale`, twelve people a frame; above them, specks of a fixed
    # 6 x 6 px (walls, windows and tree tops of PETS09): below the area floor of a person at
    # 640 x 480, above it at 0.4x, and as many per row band as there are people. The line is
    # that of the people at every scale: slope 0.25 (a ratio of pixels, so the same at every
    # scale) within 6 % and heights within 8 % where people stand.
    width, height = int(640 * scale), int(480 * scale)
    est = ForegroundSizeEstimator()
    feet = np.arange(160, 471, 3) * scale
    for start in range(0, len(feet), 12):
        y = np.ones((height, width), np.float32)
        for i, foot in enumerate(feet[start:start + 12]):
            h = int(round(0.25 * foot - 10 * scale))
            w = max(2, int(round(0.35 * h)))
            x0 = int((10 + 52 * i) * scale)
            y[int(foot) - h + 1:int(foot) + 1, x0:x0 + w] = 0.1
        est.observe(y)
    for frame in range(3):
        y = np.ones((height, width), np.float32)
        for i in range(10):
            row = int((5 + (i % 2) * 30) * scale) + 1
            y[row:row + 6, 4 + 24 * i:10 + 24 * i] = 0.2
        est.observe(y)
    line = est.person_height_line
    assert line["by_row"], line
    assert line["slope"] == pytest.approx(0.25, rel=0.06), line
    for foot in (170, 300, 460):
        at = np.clip(line["slope"] * foot * scale + line["intercept"], line["min_height"],
                     line["max_height"])
        assert at == pytest.approx((0.25 * foot - 10) * scale, rel=0.08), (foot, line)

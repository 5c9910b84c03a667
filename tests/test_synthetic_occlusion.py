"""vtrack.synthetic_occlusion: the part boxes tile the figure, the occluded fraction is the designed
one and is what the pixels show, the parts' colors tell them apart."""

import numpy as np
import pytest

import vtrack
from vtrack.synthetic_occlusion import make_occlusion_scene


@pytest.fixture(scope="module")
def person():
    return make_occlusion_scene("person", seed=3)


def test_same_seed_same_scene(person):
    again = make_occlusion_scene("person", seed=3)
    np.testing.assert_array_equal(person.frame(40), again.frame(40))
    np.testing.assert_array_equal(person.part_boxes, again.part_boxes)
    other = make_occlusion_scene("person", seed=4)
    assert not np.array_equal(person.frame(40), other.frame(40))


def test_parts_tile_the_figure_box():
    for scene in (make_occlusion_scene("person", seed=1, scale_change=0.4),
                  make_occlusion_scene("face", seed=1, occlude="upper", scale_change=-0.2)):
        b, p = scene.boxes, scene.part_boxes
        assert p.shape == (len(scene), scene.n_parts, 4)
        assert np.all(p[:, :, 0] == b[:, None, 0]) and np.all(p[:, :, 2] == b[:, None, 2])
        assert np.all(p[:, 0, 1] == b[:, 1])                                   # first part on top
        assert np.all(p[:, 1:, 1] == p[:, :-1, 1] + p[:, :-1, 3])              # rows follow on
        assert np.all(p[:, :, 3].sum(axis=1) == b[:, 3])                       # and fill the box
        assert np.all(np.abs(p[:, :, 3] - b[:, None, 3] / scene.n_parts) <= 1)  # equal shares


def test_boxes_are_the_figure_pixels_bounding_boxes(person):
    for k in (0, 30, len(person) - 1):  # unoccluded frames
        mask = person.mask(k)
        for part in range(person.n_parts):
            ys, xs = np.nonzero(mask == part + 1)
            x, y, w, h = person.part_boxes[k, part]
            assert xs.min() >= x and xs.max() < x + w and ys.min() >= y and ys.max() < y + h
        ys, xs = np.nonzero(mask > 0)
        assert (xs.min(), ys.min(), xs.max() + 1, ys.max() + 1) == tuple(
            person.boxes[k, :2]) + tuple(person.boxes[k, :2] + person.boxes[k, 2:])


@pytest.mark.parametrize("occlude, hidden", [("lower", 1), ("upper", 0)])
def test_occluded_fraction_is_as_designed(occlude, hidden):
    scene = make_occlusion_scene("person", seed=2, occlude=occlude, hidden_frames=20)
    f = scene.occluded_fraction
    visible = 1 - hidden
    assert np.all(f[:, visible] == 0.0)                                  # the other half never
    assert f[0, hidden] == 0.0 and f[-1, hidden] == 0.0                  # clean at both ends
    full = np.flatnonzero(f[:, hidden] == 1.0)
    assert len(full) == 21 and np.all(np.diff(full) == 1)                # 20 frames of speed 2 px
    rising = f[:full[0] + 1, hidden]
    assert np.all(np.diff(rising) >= 0) and np.all(np.diff(f[full[-1]:, hidden]) <= 0)
    # The ramp in and out lasts w / speed = 24 / 2 frames.
    partial = np.flatnonzero((f[:, hidden] > 0) & (f[:, hidden] < 1))
    assert 22 <= len(partial) <= 24
    np.testing.assert_array_equal(scene.occluded_frames(hidden, 1.0), full)


def test_mask_shows_the_occluder_over_the_hidden_fraction():
    scene = make_occlusion_scene("face", seed=5, occlude="lower", scale_change=0.3)
    for k in range(0, len(scene), 7):
        mask = scene.mask(k)
        for part in range(scene.n_parts):
            x, y, w, h = scene.part_boxes[k, part]
            shown = np.mean(mask[y:y + h, x:x + w] == -1)
            assert shown == pytest.approx(scene.occluded_fraction[k, part], abs=1e-12)
    # Lower occlusion of a 3-part face: the bottom third fully, the middle one half at most.
    assert scene.occluded_fraction[:, 0].max() == 0.0
    assert scene.occluded_fraction[:, 2].max() == 1.0
    assert 0.4 <= scene.occluded_fraction[:, 1].max() <= 0.6


def test_parts_colors_are_distinct_and_the_hidden_part_is_lost(person):
    """The color tools see what the scene was designed for: each part matches its own template,
    not the other's; behind the occluder the lower part's box no longer matches its template."""
    k0 = 0
    frame0 = person.frame(k0)
    upper = vtrack.image.ColorModel(frame0, person.part_boxes[k0, 0])
    lower = vtrack.image.ColorModel(frame0, person.part_boxes[k0, 1])
    assert vtrack.image.bhattacharyya_coefficient(upper.reference, lower.reference) < 0.5
    k = int(person.occluded_frames(1, 1.0)[5])
    frame = person.frame(k)
    assert upper.coefficients(frame, person.part_boxes[k, :1].astype(float))[0] > 0.8
    assert lower.coefficients(frame, person.part_boxes[k, 1:].astype(float))[0] < 0.5


def test_noise_and_scale_change():
    clean = make_occlusion_scene("person", seed=6)
    noisy = make_occlusion_scene("person", seed=6, noise_std=5.0)
    d = noisy.frame(10).astype(float) - clean.frame(10).astype(float)
    assert 4.0 < d.std() < 6.0
    grow = make_occlusion_scene("person", seed=6, scale_change=0.5)
    assert grow.boxes[0, 3] == 64 and grow.boxes[-1, 3] == 96
    centre = grow.boxes[:, 1] + grow.boxes[:, 3] / 2
    assert np.all(np.abs(centre - 120) <= 0.5)


def test_bad_arguments():
    with pytest.raises(ValueError, match="layout"):
        make_occlusion_scene("car")
    with pytest.raises(ValueError, match="occlude"):
        make_occlusion_scene(occlude="left")
    with pytest.raises(ValueError, match="speed"):
        make_occlusion_scene(speed=0)
    with pytest.raises(ValueError, match="fit"):
        make_occlusion_scene(size=(400, 64))
    with pytest.raises(ValueError, match="out of the image"):
        make_occlusion_scene(n_frames=500)
    with pytest.raises(IndexError):
        make_occlusion_scene().frame(10_000)

"""vtrack.synthetic: seeded scenes with exact ground truth, and the rendered y images."""

import numpy as np
import pytest

from vtrack.synthetic import make_scene, render_y


@pytest.fixture(scope="module")
def scene():
    return make_scene(320, 240, n_frames=200, n_people=4, seed=3, size=((14, 24), (36, 60)),
                      speed=(2.0, 3.0), enter_within=60)


def test_same_seed_same_scene(scene):
    again = make_scene(320, 240, n_frames=200, n_people=4, seed=3, size=((14, 24), (36, 60)),
                       speed=(2.0, 3.0), enter_within=60)
    np.testing.assert_array_equal(scene.frame(50), again.frame(50))
    np.testing.assert_array_equal(scene.gt_rows(), again.gt_rows())
    other = make_scene(320, 240, n_frames=200, n_people=4, seed=4)
    assert not np.array_equal(scene.frame(50), other.frame(50))


def test_frames_are_bgr_uint8_with_noise_and_illumination_change(scene):
    f0, f1 = scene.frame(0), scene.frame(1)
    assert f0.shape == (240, 320, 3) and f0.dtype == np.uint8
    assert 1.0 < np.std(f0.astype(float) - f1.astype(float)) < 10.0  # sensor noise, not more
    # Slow illumination change: the mean brightness drifts by a few percent over the scene.
    means = [scene.frame(k).mean() for k in (0, 50, 100, 150)]
    assert max(means) - min(means) > 0.04 * np.mean(means)
    with pytest.raises(IndexError):
        scene.frame(200)


def test_ground_truth_boxes_are_exact(scene):
    """An unoccluded person wholly in view has exactly its GT box as mask bounding box."""
    checked = 0
    for k in range(0, 200, 5):
        mask = scene.mask(k)
        for pid, x, y, w, h in scene.boxes(k):
            ys, xs = np.nonzero(mask == pid)
            others = scene.boxes(k)
            overlapped = any(
                o[0] != pid and o[1] < x + w and x < o[1] + o[3] and o[2] < y + h and y < o[2] + o[4]
                for o in others)
            inside = x > 0 and y > 0 and x + w < scene.width and y + h < scene.height
            if overlapped or not inside:
                continue
            assert (xs.min(), ys.min(), xs.max() + 1, ys.max() + 1) == (x, y, x + w, y + h)
            checked += 1
    assert checked > 50


def test_people_enter_cross_and_leave(scene):
    counts = [scene.count(k) for k in range(200)]
    assert counts[0] <= 1 and max(counts) == 4 and counts[-1] == 0
    gt = scene.gt_rows()
    assert set(gt[:, 1].astype(int)) == {1, 2, 3, 4}
    assert gt[:, 0].min() >= 1  # 1-based frames
    # Some walk left, some right: they cross.
    assert {np.sign(p.vx) for p in scene.people} == {-1.0, 1.0}


def test_render_y(scene):
    rng = np.random.default_rng(0)
    mask = scene.mask(60)
    y = render_y(mask, rng)
    assert y.dtype == np.float32 and y.shape == mask.shape
    assert y.min() >= 0.0 and y.max() <= 1.0
    assert y[mask != 0].mean() < 0.3 and y[mask == 0].mean() > 0.85
    clean = render_y(mask, rng, noise_std=0.0, speckle=0.0)
    assert set(np.unique(clean)) <= {np.float32(0.15), np.float32(0.95)}

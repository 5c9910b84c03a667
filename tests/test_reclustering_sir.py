"""The re-clustering SIR of particle-filters-human-vehicle §2 (vtrack.ReclusteringSirTracker and
``method="sir"``): its likelihood against a NumPy transcription of §2.1, re-clustering on
synthetic point clouds, and the whole pipeline on synthetic scenes with exact ground truth."""

import numpy as np
import pytest

import vtrack
from vtrack.evaluate import evaluate

# The scenes' ground truth is the blobs' exact extent: report the ellipses' boxes unscaled.
FOREGROUND_BOX = vtrack.pipelines.SILHOUETTE_BOX["sir"]


def numpy_log_likelihood(ellipse, points, rho, sigma, shape_power=1.0):
    """§2.1 as printed: L = N_in / (pi a b) * N_in / N * prod_j (rho + h(z_j | x)),
    h = exp(-(z - p)^T C^-1 (z - p) / 2), C = diag(sx^2, sy^2); logs; the two external factors
    raised to shape_power."""
    cx, cy, a, b = ellipse
    d = np.asarray(points, float) - (cx, cy)
    inside = np.sum((d[:, 0] / a) ** 2 + (d[:, 1] / b) ** 2 <= 1.0)
    if inside == 0:
        return -np.inf
    h = np.exp(-0.5 * ((d[:, 0] / sigma[0]) ** 2 + (d[:, 1] / sigma[1]) ** 2))
    factors = np.log(inside / (np.pi * a * b)) + np.log(inside / len(points))
    return shape_power * factors + np.sum(np.log(rho + h))


def scene_y(boxes, size=(200, 150)):
    y = np.full((size[1], size[0]), 0.95, np.float32)
    for x, top, w, h in boxes:
        y[max(top, 0):top + h, max(x, 0):x + w] = 0.1
    return y


def test_likelihood_matches_a_numpy_transcription_of_section_2_1():
    rng = np.random.default_rng(0)
    points = np.column_stack([rng.uniform(20, 80, 300), rng.uniform(10, 120, 300)])
    for _ in range(50):
        ellipse = (rng.uniform(20, 80), rng.uniform(10, 120), rng.uniform(2, 30), rng.uniform(5, 60))
        rho = float(rng.choice([1e-3, 0.1, 2.0]))
        sigma = (rng.uniform(3, 20), rng.uniform(5, 40))
        power = float(rng.choice([1.0, 31.0]))
        got = vtrack.trackers.ellipse_log_likelihood(ellipse, points, rho, sigma, power)
        want = numpy_log_likelihood(ellipse, points, rho, sigma, power)
        if np.isinf(want):
            assert got == want
        else:
            # float32 coordinates in the C++ loop: relative error ~1e-6 over 300 terms.
            assert got == pytest.approx(want, rel=1e-5, abs=1e-4)
    assert vtrack.trackers.ellipse_log_likelihood((500, 500, 5, 5), points, 0.1, (3, 5)) == -np.inf
    with pytest.raises(ValueError, match="rho"):
        vtrack.trackers.ellipse_log_likelihood((50, 50, 5, 5), points, 0.0, (3, 5))


def test_recluster_point_clouds_into_one_subset_per_object():
    """Three separated clouds: three objects, each particle in the subset of the cloud it sits
    on, the 100-particle budget shared equally (§2.2: 100 particles for 1-4 objects)."""
    boxes = [(30, 20, 12, 30), (100, 90, 12, 30), (160, 30, 12, 30)]
    centres = np.array([(x + w / 2, y + h / 2) for x, y, w, h in boxes])
    t = vtrack.ReclusteringSirTracker((200, 150), height_mean=30, size_aspect=0.4, seed=1,
                                      n_particles=100)
    for _ in range(20):
        tracks = t.step(scene_y(boxes))
    assert len(tracks) == 3 and len(t.objects) == 3
    particles, clusters = t.particles, t.clusters
    assert particles.shape == (100, 6) and clusters.shape == (100,)
    assert sorted(np.bincount(clusters)[1:]) == [33, 33, 34]
    # Each object's estimate sits on one cloud, and its particles are nearest to that cloud.
    for k, obj in enumerate(t.objects, start=1):
        cloud = np.argmin(np.hypot(*(centres - obj["estimate"][:2]).T))
        assert np.hypot(*(centres[cloud] - obj["estimate"][:2])) < 3
        mine = particles[clusters == k, :2]
        nearest = np.argmin(np.linalg.norm(mine[:, None, :] - centres[None], axis=2), axis=1)
        assert np.all(nearest == cloud)
    # Boxes: the ellipses' bounding boxes are about the 12 x 30 blobs' (§2.1's best ellipse is
    # somewhat larger than the inscribed one: N_in^2 / (pi a b) gains from the blob's corners).
    assert np.all((tracks.boxes[:, 2] > 9) & (tracks.boxes[:, 2] < 19)), tracks.boxes
    assert np.all((tracks.boxes[:, 3] > 26) & (tracks.boxes[:, 3] < 44)), tracks.boxes


def test_no_motion_then_people_in_view_and_changing_sizes():
    t = vtrack.ReclusteringSirTracker((200, 150), seed=2, n_particles=100)
    empty = scene_y([])
    for _ in range(300):  # §2.2: re-initialised every frame; nothing reported, never NaN
        assert len(t.step(empty)) == 0
    assert np.all(np.isfinite(t.particles)) and np.all(t.clusters == 0)
    for _ in range(15):
        tracks = t.step(scene_y([(40, 40, 12, 30), (140, 80, 12, 30)]))
    assert len(tracks) == 2 and np.all(np.isfinite(tracks.boxes))
    with pytest.raises(ValueError, match="y must be 150 x 200"):
        t.step(np.ones((150, 100), np.float32))
    with pytest.raises(TypeError, match="float32"):
        t.step(np.ones((150, 200)))


def scene_frame(boxes, colours, size=(200, 150)):
    """The BGR frame of scene_y's boxes: grey background, each box in its colour (later in front)."""
    frame = np.full((size[1], size[0], 3), 128, np.uint8)
    for (x, top, w, h), colour in zip(boxes, colours):
        frame[max(top, 0):top + h, max(x, 0):x + w] = colour
    return frame


def test_colours_give_the_labels_back_after_a_bounce():
    """Two people cross on one row, their blobs covering each other: the objects bounce. With the
    frames, each label goes back to the person of its colours (C++ ReclusteringSir tests count the
    seeds); without, the labels follow the objects; with appearance_rate 0 the frame changes
    nothing."""
    def run(frames, **params):
        t = vtrack.ReclusteringSirTracker((200, 150), seed=0, n_particles=100, height_mean=30,
                                          size_aspect=0.4, confirm_frames=1, lost_memory=0,
                                          **FOREGROUND_BOX, **params)
        ids = {}
        for k in range(60):
            boxes = [(20 + 3 * k, 60, 12, 30), (168 - 3 * k, 60, 12, 30)]
            y = scene_y(boxes)
            tracks = t.step(y, scene_frame(boxes, [(40, 40, 200), (200, 60, 40)])) if frames \
                else t.step(y)
            if k in (15, 45):
                iou = vtrack.evaluate.box_iou_matrix(np.array(boxes, float), tracks.boxes)
                ids[k] = [int(tracks.ids[np.argmax(row)]) if row.max() > 0.5 else 0 for row in iou]
        return ids[15], ids[45]

    before, after = run(True, appearance_rate=0.05)
    assert 0 not in before and before[0] != before[1] and after == before
    before, after = run(False, appearance_rate=0.05)
    assert after == before[::-1]
    assert run(True, appearance_rate=0.0) == (before, after)


def test_step_rejects_a_bad_frame():
    t = vtrack.ReclusteringSirTracker((200, 150), seed=0, n_particles=100)
    y = scene_y([(40, 40, 12, 30)])
    with pytest.raises(TypeError, match="frame must have dtype uint8"):
        t.step(y, np.zeros((150, 200, 3), np.float32))
    with pytest.raises(ValueError, match=r"frame must have shape \(H, W, 3\)"):
        t.step(y, np.zeros((150, 200), np.uint8))
    with pytest.raises(ValueError, match="frame must have y's size 150 x 200"):
        t.step(y, np.zeros((100, 200, 3), np.uint8))
    assert t.frame == 0


def test_parameters_by_name():
    defaults = vtrack.ReclusteringSirTracker.default_params()
    assert defaults["n_particles"] == 600 and defaults["budget_objects"] == 4
    t = vtrack.ReclusteringSirTracker((64, 48), rho=0.5, n_particles=40)
    assert t.params["rho"] == 0.5 and t.particles.shape == (40, 6)
    with pytest.raises(TypeError, match="rho"):
        vtrack.ReclusteringSirTracker((64, 48), rhoo=1.0)
    for name, value in (("n_particles", 0), ("rho", 0.0), ("rho", -1.0), ("size_min", 0.0),
                        ("size_aspect", 0.0)):
        with pytest.raises(ValueError, match=name):
            vtrack.ReclusteringSirTracker((64, 48), **{name: value})
    assert vtrack.pipelines.pipeline_params("sir")["tracker"]["rho"] == defaults["rho"]


@pytest.mark.parametrize("seed", [3, 4])
def test_tracks_synthetic_people_end_to_end(crossing_scenes, seed):
    scene, path = crossing_scenes[seed]
    rows = vtrack.track_video(path, method="sir", seed=0, **FOREGROUND_BOX)
    metrics = evaluate(scene.gt_rows(), rows)
    # Measured (tracker seeds 0 / 1 / 2): scene 3 MOTA 0.905 / 0.942 / 0.949, IDF1 0.951 /
    # 0.970 / 0.974; scene 4 0.806 / 0.949 / 0.806, 0.901 / 0.974 / 0.901 (an oversized box on
    # a person for part of the scene: 18 FP, 31 FN); no identity switch. What is lost otherwise
    # is the confirmation delay (5 frames) after each entry. One lost or duplicated person for a
    # third of the scene costs ~0.15 MOTA, so these bounds catch a real regression.
    assert metrics["MOTA"] > 0.78, metrics
    assert metrics["IDF1"] > 0.88, metrics
    assert metrics["IDSW"] <= 1, metrics
    last = len(scene) - 1
    assert np.sum(rows[:, 0] == last + 1) == scene.count(last)


def test_same_seed_same_tracks(crossing_scenes):
    _, path = crossing_scenes[3]
    a = vtrack.track_video(path, method="sir", seed=5)
    b = vtrack.track_video(path, method="sir", config={"tracker": {"seed": 5}})
    np.testing.assert_array_equal(a, b)
    c = vtrack.track_video(path, method="sir", seed=6)
    assert a.shape != c.shape or not np.array_equal(a, c)


def perspective_boxes():
    """Static people whose height grows with the foot row, h = 0.45 y_foot (PETS09-like: 27 px
    far, 106 px near, 2.6 times the learnt median), widths 0.35 h."""
    boxes = []
    for x, foot in ((20, 60), (80, 60), (140, 85), (200, 85), (260, 110), (40, 135), (120, 135),
                    (230, 236)):
        h = int(round(0.45 * foot))
        w = int(round(0.35 * h))
        boxes.append((x - w // 2, foot - h, w, h))
    return boxes


def objects_on_boxes(tracker, boxes):
    """Per box, the objects whose estimate centre lies within (w, h / 2) of the box's centre."""
    out = []
    for x, top, w, h in boxes:
        c = np.array([x + w / 2, top + h / 2])
        out.append([o["estimate"] for o in tracker.objects
                    if abs(o["estimate"][0] - c[0]) < w and abs(o["estimate"][1] - c[1]) < h / 2])
    return out


@pytest.mark.parametrize("seed", [0, 1])
def test_size_by_row_sizes_each_person_at_its_row(seed):
    """size_by_row: the person size follows the learnt line of component height by foot row, so
    a near person 2.6 times the median height is one object with axes fitted to it, and far ones
    are not inflated. The truth is the blobs' own extent; the ratios allow §2.1's best ellipse,
    somewhat larger than the inscribed one (as above: 26-44 px for 30 px blobs). Measured with
    seeds 0-2: 8 objects, 2b / h 0.95-1.37, 2a / w 0.96-1.08. Without size_by_row the near
    person is cut into several objects (6 measured) and the 61 px ones into two halves."""
    boxes = perspective_boxes()
    y = scene_y(boxes, size=(320, 240))
    for by_row, want in ((True, 1), (False, None)):
        t = vtrack.ReclusteringSirTracker((320, 240), seed=seed, size_by_row=by_row)
        for _ in range(40):
            t.step(y)
        found = objects_on_boxes(t, boxes)
        if by_row:
            assert len(t.objects) == len(boxes)
            for (x, top, w, h), objs in zip(boxes, found):
                assert len(objs) == want, (x, top, w, h)
                assert 0.85 < 2 * objs[0][5] / h < 1.5 and 0.85 < 2 * objs[0][4] / w < 1.3
        else:
            assert len(found[-1]) >= 2  # the near person split: what size_by_row fixes

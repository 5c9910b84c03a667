"""vtrack.MultiBernoulliTracker: API, bad input, and end to end on a synthetic scene."""

import threading

import numpy as np
import pytest

import vtrack
from vtrack.evaluate import box_iou_matrix, evaluate
from vtrack.io import mot_rows, read_mot, write_mot
from vtrack.synthetic import make_scene, render_y


# The paper's track output (Section 4): every component with r > 0.5 reported at once under its
# birth label, random-walk prediction, the estimated box itself (the defaults add confirmation,
# a lost-track memory, a velocity drift and PETS09's box calibration; see multi_bernoulli.hpp).
PAPER_OUTPUT = dict(confirm_frames=1, lost_memory=0, velocity_smoothing=0.0, box_scale_w=1.0,
                    box_scale_h=1.0, box_offset_x=0.0, box_offset_y=0.0)


def background(width=160, height=120):
    return np.full((height, width), 0.95, np.float32)


def test_defaults_and_params():
    d = vtrack.MultiBernoulliTracker.default_params()
    assert d["survival_probability"] == pytest.approx(0.99)
    assert d["birth_probability"] == pytest.approx(0.02)  # the paper's r_Gamma
    assert d["prune_threshold"] == pytest.approx(0.01)
    assert d["estimate_threshold"] == pytest.approx(0.5)
    t = vtrack.MultiBernoulliTracker((160, 120), seed=1, delta_f=0.2, max_particles=100,
                                     quarter_birth=False, resampling="residual")
    assert t.params["delta_f"] == 0.2 and t.params["max_particles"] == 100
    assert t.params["quarter_birth"] is False and t.params["resampling"] == "residual"
    assert t.image_size == (160, 120) and t.frame == 0
    assert len(t.step(np.ones((120, 160), np.float32))) == 0 and t.frame == 1


@pytest.mark.parametrize("kwargs, exc, words", [
    ({"survival_probability": 0.0}, ValueError, "survival_probability"),
    ({"survival_probability": 1.01}, ValueError, "survival_probability"),
    ({"min_particles": 500, "max_particles": 100}, ValueError, "min_particles"),
    ({"sigma_xy": 0.0}, ValueError, "sigma_xy"),
    ({"sigma_wh": -1}, ValueError, "sigma_wh"),
    ({"delta_b": 0}, ValueError, "delta_b"),
    ({"delta_b_no_line": float("nan")}, ValueError, "delta_b_no_line"),
    ({"delta_b_reference": "screen"}, ValueError, "screen"),
    ({"delta_b_reference": "row", "size_by_row": False}, ValueError, "size_by_row"),
    ({"sigma_xy": "2"}, TypeError, "sigma_xy"),
    ({"sigma_x": 5.0}, TypeError, "sigma_xy"),  # the former pixel name: did you mean
    ({"height_mean": -1.0}, ValueError, "height_mean"),
    ({"adaptive_birth_stride": 8}, ValueError, "adaptive_birth_stride"),
    ({"max_particles": 10.5}, TypeError, "max_particles"),
    ({"quarter_birth": 1}, TypeError, "quarter_birth"),
    ({"resampling": "bogus"}, ValueError, "bogus"),
    ({"no_such_param": 1}, TypeError, "no_such_param"),
    ({"confirm_frames": 0}, ValueError, "confirm_frames"),
    ({"velocity_smoothing": -0.1}, ValueError, "velocity_smoothing"),
    ({"box_scale_h": 0.0}, ValueError, "box_scale_h"),
])
def test_bad_parameters(kwargs, exc, words):
    with pytest.raises(exc, match=words):
        vtrack.MultiBernoulliTracker((160, 120), **kwargs)


def test_bad_image_size_and_images():
    with pytest.raises(TypeError, match="image_size"):
        vtrack.MultiBernoulliTracker(160)
    with pytest.raises(TypeError, match="image_size"):
        vtrack.MultiBernoulliTracker((160, 120, 3))
    with pytest.raises(ValueError, match="width"):
        vtrack.MultiBernoulliTracker((0, 120))
    t = vtrack.MultiBernoulliTracker((160, 120), seed=np.uint64(3))
    with pytest.raises(TypeError, match="y must have dtype float32"):
        t.step(background().astype(np.float64))
    with pytest.raises(ValueError, match="120 x 160"):
        t.step(np.ones((120, 161), np.float32))
    with pytest.raises(ValueError, match="y"):
        t.step(np.ones((120, 160, 1), np.float32))
    y = background()
    y[5, 7] = np.nan
    with pytest.raises(ValueError, match="row 5, column 7"):
        t.step(y)
    assert t.frame == 0


def test_one_person_one_label_and_components_exposed():
    # A user who knows the scene: a 12 x 30 px prior in pixels (no learning).
    t = vtrack.MultiBernoulliTracker((160, 120), seed=2, width_mean=12, height_mean=30,
                                     size_std=0.22, size_max=1.8, **PAPER_OUTPUT)
    assert t.size_prior["width"] == 12 and t.size_prior["height"] == 30
    labels = set()
    for k in range(20):
        y = background()
        y[50:80, 40 + k:52 + k] = 0.1
        tracks = t.step(y)
        if k >= 3:
            assert len(tracks) == 1
            labels.add(int(tracks.ids[0]))
            x, yy, w, h = tracks.boxes[0]
            assert abs(x - (40 + k)) < 3 and abs(yy - 50) < 3
            assert 0.5 < tracks.scores[0] <= 1.0
            # The filter's own box is the state: the reported box calibrated (scales 1 here).
            np.testing.assert_allclose(tracks.states[0], tracks.boxes[0], rtol=1e-6)
    assert len(labels) == 1
    assert repr(tracks) == f"Tracks(ids=[{labels.pop()}])"
    comps = t.components
    assert any(c.label == tracks.ids[0] for c in comps)
    c = comps[0]
    assert c.particles.shape == (len(c.weights), 4) and c.particles.dtype == np.float32
    assert c.weights.sum() == pytest.approx(1.0)
    assert t.tracks.ids[0] == tracks.ids[0]
    # Snapshots stay valid after further steps (they are copies, not views into the filter).
    before = [(c.label, c.existence, c.particles.copy()) for c in comps]
    for _ in range(3):
        t.step(background())
    assert [(c.label, c.existence) for c in comps] == [b[:2] for b in before]
    assert all(np.array_equal(c.particles, b[2]) for c, b in zip(comps, before))


def _walk_side_by_side(tracker, gap, frames, seed, person, start=(60, 90), speed=1.5):
    """Two rendered people gap px apart walking right together; per frame the tracks and the
    true boxes."""
    rng = np.random.default_rng(seed)
    width, height = tracker.image_size
    pw, ph = person
    out = []
    for k in range(frames):
        x0 = int(round(start[0] + speed * k))
        truth = np.array([[x0, start[1], pw, ph], [x0 + pw + gap, start[1], pw, ph]], float)
        mask = np.zeros((height, width), np.uint8)
        for x, y, w, h in truth.astype(int):
            mask[y:y + h, x:x + w] = 1
        out.append((tracker.step(render_y(mask, rng)), truth))
    return out


def _assert_two_tracks(gap, seed, frames=80, settle=10, output=PAPER_OUTPUT):
    # PETS09-S2L1's people at its resolution: 30 x 85 px in 768 x 576, the prior in pixels.
    t = vtrack.MultiBernoulliTracker((768, 576), seed=seed, width_mean=30.0, height_mean=85.0,
                                     **output)
    for k, (tracks, truth) in enumerate(_walk_side_by_side(t, gap, frames, seed, (30, 85))):
        if k < settle:
            continue
        assert len(tracks) == 2, (k, tracks.boxes)
        iou = box_iou_matrix(truth, np.asarray(tracks.boxes))
        # > 0.3: where two people touch, eq. (20) leaves the boundary between their boxes
        # loose (PETS09: groups cost box accuracy, benchmarks/mb_groups.py).
        assert iou.max(axis=1).min() > 0.3, (k, tracks.boxes)
        assert set(iou.argmax(axis=1)) == {0, 1}, (k, tracks.boxes)  # one track per person


@pytest.mark.parametrize("seed", [0, 1])
def test_two_people_walking_close_hold_two_tracks(seed):
    # Two people walking 8 px apart (two blobs after the 5 px closing): one Bernoulli per person,
    # each matched by their own track from frame 10 to 80. Independent truth: the rendered boxes.
    _assert_two_tracks(gap=8, seed=seed)


@pytest.mark.xfail(strict=True, reason="known failure in groups (issue 12, benchmarks/"
                   "mb_groups.py): with the paper's random walk a touching pair is held by two "
                   "tracks for ~30 frames, then the older component's box widens over both and "
                   "the other, its pixels explained (eq. 13), dies")
def test_two_touching_people_hold_two_tracks():
    # 2 px apart: one foreground blob after the closing. Seeds 0-3 all fall to one track between
    # frames 31 and 45 (seed 3 never holds two); strict, so a fix shows up as XPASS.
    _assert_two_tracks(gap=2, seed=0)


@pytest.mark.parametrize("seed", [0, 1])
def test_two_touching_people_hold_two_tracks_with_the_default_track_management(seed):
    # The same pair with the defaults (the foreground box reported): the velocity drift
    # (velocity_smoothing) moves both boxes with the pair, so neither widens over the other;
    # seeds 0-3 at 0 and 2 px apart held two tracks to frame 80 in 7 of 8 runs (seed 3 at 0 px:
    # one track throughout). Confirmation (5 reports) delays the first tracks to frame 7-8.
    _assert_two_tracks(gap=2, seed=seed, settle=12,
                       output=dict(box_scale_w=1.0, box_scale_h=1.0, box_offset_x=0.0,
                                   box_offset_y=0.0))


def test_a_person_cut_by_the_border_is_boxed_as_the_whole_person():
    # A 24 x 60 px person with half of it out of view at the left border, in a 320 x 240 image,
    # the prior's size given. The filter's own box (the track's state) covers the part in view,
    # [0, R]. Annotations box the whole person with a margin and clip that to the image, so the
    # reported box is the calibration of the whole person's box [R - 24, R] (prior width 24),
    # clipped: right edge R - 12 + box_offset_x x 24 + box_scale_w x 12, ~4 px beyond where the
    # calibrated part in view would end. A person in view keeps its own box, calibrated.
    d = vtrack.MultiBernoulliTracker.default_params()
    t = vtrack.MultiBernoulliTracker((320, 240), seed=2, width_mean=24, height_mean=60)
    for _ in range(15):
        y = background(320, 240)
        y[100:160, 0:12] = 0.1
        y[100:160, 198:222] = 0.1
        tracks = t.step(y)
    assert len(tracks) == 2, tracks.boxes
    order = np.argsort(np.asarray(tracks.boxes)[:, 0])
    (cut, inside), (cut_state, inside_state) = (np.asarray(tracks.boxes)[order],
                                                np.asarray(tracks.states)[order])
    right = cut_state[0] + cut_state[2]
    assert cut_state[0] < 1.0 and 6.0 < right < 14.0, cut_state
    assert cut[0] == 0.0, cut
    whole_right = right - 12.0 + d["box_offset_x"] * 24 + d["box_scale_w"] * 12
    part_right = right * (0.5 + d["box_offset_x"] + 0.5 * d["box_scale_w"])
    assert whole_right - part_right > 3.0  # the two conventions are told apart
    assert cut[0] + cut[2] == pytest.approx(whole_right, abs=1e-3), (cut, cut_state)
    x, _, w, _ = inside_state
    assert inside[2] == pytest.approx(d["box_scale_w"] * w, abs=1e-3), (inside, inside_state)
    assert inside[0] + 0.5 * inside[2] == pytest.approx(x + 0.5 * w + d["box_offset_x"] * w,
                                                        abs=1e-3)


@pytest.mark.parametrize("clip", [True, False])
def test_box_clip_keeps_a_person_half_out_of_view_in_the_image(clip):
    # A person 12 x 30 px whose left half is out of view, standing at the left border: the
    # filter's box is the visible half, which the calibration (PETS09's 1.673 x 1.706 by
    # default) scales about its centre, over the border. Annotations box what is in view, so
    # with box_clip (MB's default) the reported box ends at the border; without it, it does not.
    t = vtrack.MultiBernoulliTracker((160, 120), seed=2, width_mean=12, height_mean=30,
                                     box_clip=clip)
    for _ in range(12):
        y = background()
        y[50:80, 0:6] = 0.1
        tracks = t.step(y)
    assert len(tracks) == 1
    x, _, w, _ = tracks.boxes[0]
    if clip:
        assert x == 0.0 and 5.0 < w < 12.0, tracks.boxes
    else:
        assert x < -1.0, tracks.boxes


def test_all_background_and_all_foreground_no_nan():
    t = vtrack.MultiBernoulliTracker((160, 120), seed=3)
    for y in (np.ones((120, 160), np.float32), np.zeros((120, 160), np.float32)):
        for _ in range(5):
            tracks = t.step(y)
            assert np.all(np.isfinite(tracks.boxes)) and np.all(np.isfinite(tracks.scores))
        assert all(np.all(np.isfinite(c.particles)) for c in t.components)


# The synthetic ground-truth boxes are the blobs' exact extents, not a margin-annotated box like
# MOT15's: report the silhouette's box (the default box_scale_* and box_offset_* map to PETS09's
# annotation convention).
FOREGROUND_BOX = vtrack.pipelines.SILHOUETTE_BOX["mb"]


def run(scene, seed=0, **params):
    """Tracks of the scene's rendered y images, as MOT rows, and the per-frame counts."""
    tracker = vtrack.MultiBernoulliTracker((scene.width, scene.height), seed=seed,
                                           **{**FOREGROUND_BOX, **params})
    rng = np.random.default_rng(100 + seed)
    rows, counts = [np.zeros((0, 10))], []
    for k in range(len(scene)):
        tracks = tracker.step(render_y(scene.mask(k), rng))
        rows.append(mot_rows(k + 1, tracks))
        counts.append(len(tracks))
    return np.vstack(rows), counts


@pytest.fixture(scope="module")
def pets_like_scene():
    # PETS09-S2L1-like: 768 x 576, people 25-60 x 70-140 px walking 3-5 px/frame (7 frames/s),
    # six of them entering from both sides within 100 frames, crossing, the last leaving at 315.
    return make_scene(768, 576, n_frames=330, n_people=6, seed=1, size=((25, 60), (70, 140)),
                      speed=(3.0, 5.0), enter_within=100)


def test_end_to_end_metrics_and_counts(pets_like_scene, tmp_path):
    """The default parameters on a 768 x 576 scene.

    Measured on this scene (seed 1) with tracker seeds 0-3: MOTA 0.93, IDF1 0.97, no ID switch;
    other scene seeds: 0.93-0.94 (2, 5, 6), 0.89 (3), 0.58 (4, two people walking as one blob,
    a limit of the model) -- with the first defaults. With the current ones (confirm_frames 5,
    velocity drift, lost-track memory; foreground box reported): MOTA 0.91, IDF1 0.95, no ID
    switch (tracker seeds 0, 1). The errors left are latencies: a person counts in the ground
    truth once a quarter of the box is in view, and a track is reported 5-7 frames later; a track
    outlives its person by about one frame. Six people x ~4 frames of latency of ~1100 GT boxes
    bounds MOTA near 0.95. The thresholds (MOTA > 0.85, IDF1 > 0.9) leave room for the seeds,
    and fail on real regressions (a lost, split or duplicated track costs ~0.1 MOTA).
    """
    scene = pets_like_scene
    rows, counts = run(scene, seed=0)
    write_mot(tmp_path / "tracks.txt", rows)
    write_mot(tmp_path / "gt.txt", scene.gt_rows())
    m = evaluate(read_mot(tmp_path / "gt.txt"), read_mot(tmp_path / "tracks.txt"))
    assert m["MOTA"] > 0.85, m
    assert m["IDF1"] > 0.9, m
    assert m["IDSW"] <= 2, m
    truth = [scene.count(k) for k in range(len(scene))]
    # The right count once entries have settled: the frames where everyone has been in view for
    # 5 frames (entry latency) and nobody leaves within 3 frames.
    settled = [k for k in range(5, len(scene) - 3)
               if len(set(truth[k - 5:k + 4])) == 1]
    # Measured with the learnt size prior (issue 12): 230 and 235 of 245 (tracker seeds 0, 1;
    # MOTA 0.902 / 0.885, IDF1 0.950 / 0.941); 0.95 of them with the fixed 30 x 85 prior before.
    right = sum(counts[k] == truth[k] for k in settled)
    assert right >= 0.9 * len(settled), (right, len(settled))
    # Everyone leaves, and the tracker reports nobody within 3 frames of the last exit.
    last = max(k for k in range(len(scene)) if truth[k] > 0)
    assert max(truth) == 6 and last + 4 < len(scene)
    assert counts[last + 4:] == [0] * (len(scene) - last - 4)


def test_same_seed_same_tracks_and_threads(pets_like_scene):
    scene = pets_like_scene
    rng = np.random.default_rng(5)
    ys = [render_y(scene.mask(k), rng) for k in range(60, 90)]

    def tracks_of(out, index):
        t = vtrack.MultiBernoulliTracker((768, 576), seed=11)
        out[index] = [mot_rows(1, t.step(y)).tolist() for y in ys]

    results = [None] * 3
    tracks_of(results, 0)
    threads = [threading.Thread(target=tracks_of, args=(results, i)) for i in (1, 2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert results[0] == results[1] == results[2]
    assert any(results[0])

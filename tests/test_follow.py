"""The single-object colour trackers (part-based-graphical-model-pf.txt): vtrack.ColorParticleTracker
and vtrack.PartParticleTracker against the exact part truth of vtrack.synthetic_occlusion, the
OpenCV-like surface, determinism and bad input. (The C++ suite test_color_particle.cpp checks the
equations: eq. 13, eq. 21's geometry, eqs. 24-29's weights, eqs. 27-30's draw frequencies.)"""

import numpy as np
import pytest

import vtrack
from vtrack.synthetic_occlusion import make_occlusion_scene


def centre(box):
    return np.array([box[0] + box[2] / 2, box[1] + box[3] / 2])


def run(scene, tracker):
    """Per frame 1..n-1: (object box, part boxes or None, occluded flags or None)."""
    tracker.init(scene.frame(0), scene.boxes[0])
    out = []
    for k in range(1, len(scene)):
        ok, box = tracker.update(scene.frame(k))
        assert ok
        parts = getattr(tracker, "parts", None)
        occluded = tracker.occluded if parts is not None else None
        out.append((np.array(box), None if parts is None else np.array(parts), occluded))
    return out


@pytest.mark.parametrize("layout,occlude", [("person", "lower"), ("person", "upper"),
                                            ("face", "lower")])
def test_part_based_infers_the_hidden_part_and_the_conventional_filter_drifts(layout, occlude):
    # While a part is hidden (occluded fraction > 0.9) the part-based filter judges it occluded
    # and its estimate, inferred from the visible parts, stays on its exact truth: horizontally
    # within a quarter of the part's width; vertically within a quarter of the object's height at
    # worst and a sixth on average (vertically the visible part's scale is uncertain -- a colour
    # histogram barely changes with a box's height inside a uniform region -- and eq. 21's offset
    # scales with it; a face's middle third is half hidden too and shifts up). Over the occlusion the conventional filter's box drifts further from the truth than the
    # part-based filter's object box.
    scene = make_occlusion_scene(layout, seed=0, occlude=occlude, noise_std=4.0)
    parts = run(scene, vtrack.PartParticleTracker(parts=scene.n_parts, n_particles=30, seed=0))
    color = run(scene, vtrack.ColorParticleTracker(seed=0))
    hidden_errors, judged, part_obj, color_obj = [], [], [], []
    for k in range(1, len(scene)):
        hidden = np.flatnonzero(scene.occluded_fraction[k] > 0.9)
        box, part_boxes, occluded = parts[k - 1]
        for p in hidden:
            hidden_errors.append(np.abs(centre(part_boxes[p]) - centre(scene.part_boxes[k, p])))
            judged.append(occluded[p])
        if scene.occluded_fraction[k].max() > 0.25:
            part_obj.append(np.linalg.norm(centre(box) - centre(scene.boxes[k])))
            color_obj.append(np.linalg.norm(centre(color[k - 1][0]) - centre(scene.boxes[k])))
    assert len(hidden_errors) >= 15
    part_w, height = scene.part_boxes[0, 0, 2], scene.boxes[0, 3]
    worst, mean = np.max(hidden_errors, axis=0), np.mean(hidden_errors, axis=0)
    assert worst[0] < part_w / 4 and worst[1] < height / 4 and mean[1] < height / 6, (worst, mean)
    assert np.mean(judged) > 0.9
    assert np.max(part_obj) < np.max(color_obj), (np.max(part_obj), np.max(color_obj))


def test_opencv_like_surface_and_determinism():
    scene = make_occlusion_scene("person", seed=1)
    for cls in (vtrack.ColorParticleTracker, vtrack.PartParticleTracker):
        tracks = []
        for seed in (3, 3, 4):
            t = cls(seed=seed)
            assert t.init(scene.frame(0), tuple(scene.boxes[0])) is None
            boxes = [t.update(scene.frame(k))[1] for k in range(1, 12)]
            tracks.append(np.array(boxes))
        np.testing.assert_array_equal(tracks[0], tracks[1])
        assert not np.array_equal(tracks[0], tracks[2])
    c = vtrack.ColorParticleTracker(n_particles=40)
    c.init(scene.frame(0), scene.boxes[0])
    ok, box = c.update(scene.frame(1))
    assert ok is True and len(box) == 4
    assert c.particles.shape == (40, 4) and c.weights.shape == (40,)
    assert np.isclose(c.weights.sum(), 1.0) and np.all(np.isfinite(c.weights))
    assert 0.0 <= c.coefficient <= 1.0
    p = vtrack.PartParticleTracker(parts=3, n_particles=10, edges=[(0, 1), (1, 2)])
    p.init(scene.frame(0), scene.boxes[0])
    p.update(scene.frame(1))
    assert p.parts.shape == (3, 4) and p.occluded.shape == (3,) and p.occluded.dtype == bool
    # Step 5's sets: (1 + degree) N particles per part on the chain 0 - 1 - 2.
    assert [len(x) for x in p.particles] == [20, 30, 20]
    assert all(np.isclose(w.sum(), 1.0) for w in p.weights)
    assert p.params["parts"] == 3 and p.edges == [(0, 1), (1, 2)]
    # Any layout: fractions of the box.
    q = vtrack.PartParticleTracker(parts=[(0, 0, 1, 0.3), (0, 0.3, 1, 0.7)])
    q.init(scene.frame(0), scene.boxes[0])
    x, y, w, h = scene.boxes[0]
    np.testing.assert_allclose(q.parts[1], (x, y + 0.3 * h, w, 0.7 * h))


def test_bad_input():
    scene = make_occlusion_scene("person", seed=1)
    f0 = scene.frame(0)
    for cls in (vtrack.ColorParticleTracker, vtrack.PartParticleTracker):
        t = cls()
        with pytest.raises(ValueError, match="before init"):
            t.update(f0)
        with pytest.raises(ValueError, match="positive width"):
            t.init(f0, (10, 10, 0, 20))
        with pytest.raises(ValueError, match="box"):
            t.init(f0, (10, 10, np.nan, 20))
        with pytest.raises(ValueError, match="no pixel"):
            t.init(f0, (1000, 10, 20, 20))
        black = f0.copy()
        black[10:30, 10:30] = 0
        with pytest.raises(ValueError, match="all black"):
            t.init(black, (10, 10, 20, 20))
        with pytest.raises(TypeError, match="sigm"):
            cls(sigm=0.2)
        with pytest.raises(ValueError, match="sigma"):
            cls(sigma=float("nan"))
        t.init(f0, scene.boxes[0])
        with pytest.raises(ValueError, match="init saw"):
            t.update(f0[:100])
    with pytest.raises(ValueError, match="edges"):
        vtrack.PartParticleTracker(edges=[(0, 5)])


def test_target_leaving_the_image_is_not_ok():
    # A figure walking out of the right border (frames cut at column 120; it starts at x = 10 and
    # moves 2 px per frame, so it has left by frame 56): ok becomes False, weights stay finite.
    scene = make_occlusion_scene("person", seed=2, hidden_frames=0)
    assert scene.boxes[0, 0] == 10 and scene.boxes[56, 0] >= 120
    for t in (vtrack.ColorParticleTracker(), vtrack.PartParticleTracker()):
        t.init(scene.frame(0)[:, :120], scene.boxes[0])
        oks = []
        for k in range(1, 90):
            oks.append(t.update(scene.frame(k)[:, :120])[0])
            weights = t.weights if isinstance(t.weights, list) else [t.weights]
            assert all(np.all(np.isfinite(w)) for w in weights)
        assert all(oks[:30]) and not oks[-1]


# ---- the follow pipeline: vtrack.follow and `vtrack follow` --------------------------------------

def _exe():
    import sysconfig
    from pathlib import Path
    return Path(sysconfig.get_path("scripts")) / "vtrack"


@pytest.fixture(scope="module")
def occlusion_video(tmp_path_factory):
    """The person scene's first 40 frames as an MJPG .avi, and the scene."""
    import cv2
    scene = make_occlusion_scene("person", seed=3, noise_std=2.0)
    path = tmp_path_factory.mktemp("follow") / "scene.avi"
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 25,
                             (scene.width, scene.height))
    for k in range(40):
        writer.write(scene.frame(k))
    writer.release()
    return path, scene


def test_follow_matches_the_tracker_and_the_cli(occlusion_video, tmp_path):
    import subprocess
    import cv2
    path, scene = occlusion_video
    box = tuple(float(v) for v in scene.boxes[4])
    rows = vtrack.follow(path, box, method="parts", first=5, last=30, seed=7, n_particles=20)
    # Rows for frames 5..30, the first the init box; the tracker run by hand on the decoded
    # frames (index k holds frame k + 1) gives the same boxes.
    assert rows.shape == (26, 5) and rows[0, 0] == 5 and rows[-1, 0] == 30
    np.testing.assert_allclose(rows[0, 1:], box)
    cap = cv2.VideoCapture(str(path))
    frames = [cap.read()[1] for _ in range(30)]
    t = vtrack.PartParticleTracker(seed=7, n_particles=20)
    t.init(frames[4], box)
    expected = [t.update(frames[k - 1])[1] for k in range(6, 31)]
    np.testing.assert_allclose(rows[1:, 1:], expected)
    # The CLI writes the same rows, to 2 decimals.
    out, render = tmp_path / "t.txt", tmp_path / "r.avi"
    result = subprocess.run([str(_exe()), "follow", str(path), "--init", ",".join(map(str, box)),
                             "--first", "5", "--last", "30", "--method", "parts", "--seed", "7",
                             "--particles", "20", "--out", str(out), "--render", str(render)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    written = np.loadtxt(out, delimiter=",")
    np.testing.assert_allclose(written, rows, atol=0.006)
    assert cv2.VideoCapture(str(render)).get(cv2.CAP_PROP_FRAME_COUNT) == 26


@pytest.mark.parametrize("args,word", [
    (["--init", "300,10,30,30"], "leaves"),
    (["--init", "10,10,0,30"], "positive width"),
    (["--init", "10,10,20,30", "--first", "41"], "past the end"),
])
def test_follow_cli_bad_box_and_frames(occlusion_video, tmp_path, args, word):
    import subprocess
    path, _ = occlusion_video
    out = tmp_path / "t.txt"
    result = subprocess.run([str(_exe()), "follow", str(path), *args, "--out", str(out)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 1 and word in result.stderr, result.stderr
    assert not out.exists() and list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match=word):
        box = [float(v) for v in args[1].split(",")]
        vtrack.follow(path, box, first=int(args[3]) if len(args) > 2 else 1)


def test_one_tracker_updated_from_two_threads_is_serialised():
    # update() releases the GIL and holds the object's guard: 2 x 6 updates of one frame from two
    # threads give what 12 serial updates give.
    import threading
    scene = make_occlusion_scene("person", seed=1)
    f0, f1 = scene.frame(0), scene.frame(1)
    for cls in (vtrack.ColorParticleTracker, vtrack.PartParticleTracker):
        serial = cls(seed=5)
        serial.init(f0, scene.boxes[0])
        for _ in range(12):
            expected = serial.update(f1)
        shared = cls(seed=5)
        shared.init(f0, scene.boxes[0])
        threads = [threading.Thread(target=lambda: [shared.update(f1) for _ in range(6)])
                   for _ in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert shared.box == expected[1]


def test_follow_config_file_and_keywords_agree(occlusion_video, tmp_path):
    # A config file's tracker section and top-level seed set what keywords set.
    path, scene = occlusion_video
    box = tuple(float(v) for v in scene.boxes[0])
    config = tmp_path / "follow.yml"
    config.write_text("seed: 11\ntracker: {n_particles: 12, sigma: 0.25}\n")
    from_file = vtrack.follow(path, box, last=15, config=config)
    from_keywords = vtrack.follow(path, box, last=15, seed=11, n_particles=12, sigma=0.25)
    np.testing.assert_array_equal(from_file, from_keywords)
    assert not np.array_equal(from_keywords, vtrack.follow(path, box, last=15, seed=11))
    with pytest.raises(ValueError, match="sections"):
        vtrack.follow(path, box, config={"background": {}})
    with pytest.raises(TypeError, match="n_particle"):
        vtrack.follow(path, box, n_particle=3)

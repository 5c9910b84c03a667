"""The synthetic road-scene generator: determinism, realistic dimensions, and ground truth that
agrees with what it renders (boxes and silhouettes from cv2.projectPoints vs pixels from ray
casting through cv2.undistortPoints)."""

import csv
import dataclasses
import hashlib
import json

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2")

import vtrack  # noqa: E402
from vtrack.synthetic_road import CAMERA_SETUPS, VEHICLE_CLASSES, make_road_scene, read_ground_truth  # noqa: E402


def small(name, scale=3.0):
    """A preset at a third of its resolution (same field of view), so tests take seconds."""
    s = CAMERA_SETUPS[name]
    return dataclasses.replace(s, image_width=int(s.image_width / scale), image_height=int(s.image_height / scale),
                               focal=s.focal / scale)


@pytest.fixture(scope="module")
def scenes():
    return {name: make_road_scene(small(name), n_vehicles=10, seed=5) for name in CAMERA_SETUPS}


def sampled_frames(scene, step=15):
    return range(0, scene.n_frames, step)


def test_same_seed_same_video_other_seed_other_video(tmp_path):
    # 5 frames per second: a short video (the vehicles move 4-6 m per frame).
    a = make_road_scene(small("mast_low"), n_vehicles=3, seed=3, fps=5.0)
    b = make_road_scene(small("mast_low"), n_vehicles=3, seed=3, fps=5.0)
    c = make_road_scene(small("mast_low"), n_vehicles=3, seed=4, fps=5.0)
    k = a.n_frames // 3
    assert a.n_frames == b.n_frames
    assert np.array_equal(a.frame(k), b.frame(k))
    assert [(v.cls, v.W, v.L, v.enter) for v in a.vehicles] == [(v.cls, v.W, v.L, v.enter) for v in b.vehicles]
    assert not np.array_equal(a.frame(k), c.frame(k))
    digests = []
    for scene, folder in ((a, "a"), (b, "b")):
        paths = scene.write(tmp_path / folder, video="v.avi")
        digests.append({name: hashlib.sha256(p.read_bytes()).hexdigest() for name, p in paths.items()})
    assert digests[0] == digests[1]


def test_dimensions_are_realistic_and_varied():
    scene = make_road_scene(small("mast_high"), n_vehicles=400, seed=1)
    classes = {v.cls for v in scene.vehicles}
    assert classes == set(VEHICLE_CLASSES)  # 400 draws reach every class
    for v in scene.vehicles:
        spec = VEHICLE_CLASSES[v.cls]
        assert v.heavy == spec["heavy"]
        for dim in ("W", "H", "L"):
            lo, hi = spec[dim]
            assert lo <= getattr(v, dim) <= hi
        assert 0.0 <= v.x0 and v.x0 + v.W <= scene.n_lanes * scene.lane_width  # inside the road
        assert v.x0 >= v.lane * scene.lane_width and v.x0 + v.W <= (v.lane + 1) * scene.lane_width
    cars = np.array([[v.W, v.H, v.L] for v in scene.vehicles if v.cls == "car"])
    assert (cars.std(axis=0) > [0.05, 0.08, 0.3]).all()  # not Table 1's means
    heavy = np.mean([v.heavy for v in scene.vehicles])
    assert 0.1 < heavy < 0.25
    assert [v.id for v in scene.vehicles] == list(range(1, 401))
    assert all(a.enter <= b.enter for a, b in zip(scene.vehicles, scene.vehicles[1:]))


def test_vehicles_of_a_lane_never_overlap():
    scene = make_road_scene(small("gantry"), n_vehicles=60, seed=2)
    for k in range(0, scene.n_frames, 7):
        t = scene.time(k)
        by_lane = {}
        for v in scene.present(k):
            y0 = v.y0(t, scene.y_range)
            by_lane.setdefault(v.lane, []).append((y0, y0 + v.L))
        for spans in by_lane.values():
            spans.sort()
            assert all(a[1] < b[0] for a, b in zip(spans, spans[1:]))


def test_boxes_contain_the_rendered_silhouettes_tightly(scenes):
    checked = 0
    for name, scene in scenes.items():
        for k in sampled_frames(scene):
            _, ids, rows = scene.frame_with_truth(k)
            for vid, x, y, w, h, in_view, visible in rows:
                v = scene.vehicles[int(vid) - 1]
                ys, xs = np.nonzero(scene.vehicle_mask(v, k))
                assert xs.min() >= x and xs.max() <= x + w and ys.min() >= y and ys.max() <= y + h, name
                if in_view:  # the exact box is tight: no more than ~1 px beyond the pixel centres
                    assert max(xs.min() - x, ys.min() - y, x + w - xs.max(), y + h - ys.max()) < 1.5, name
                    checked += 1
                # visible = share of the vehicle's pixels that the id map gives to it
                assert visible == pytest.approx(np.mean(ids[ys, xs] == vid))
    assert checked > 60


def test_silhouettes_contain_the_rendered_pixels(scenes):
    for name, scene in scenes.items():
        for k in sampled_frames(scene, step=23):
            for v in scene.present(k):
                poly = scene.silhouette(v, k)
                if poly is None:
                    continue
                ys, xs = np.nonzero(scene.vehicle_mask(v, k))
                contour = poly.astype(np.float32).reshape(-1, 1, 2)
                inside = [cv2.pointPolygonTest(contour, (float(px), float(py)), True) for px, py in zip(xs, ys)]
                assert min(inside) > -0.05, name  # every hit pixel centre inside the polygon


def test_scenes_have_occlusions_and_overlapping_boxes(scenes):
    occluded = overlapping = 0
    for scene in scenes.values():
        for k in sampled_frames(scene, step=16):
            rows = scene.boxes(k)
            occluded += int((rows[:, 6] < 0.9).sum())
            for i in range(len(rows)):
                for j in range(i + 1, len(rows)):
                    a, b = rows[i, 1:5], rows[j, 1:5]
                    overlapping += a[0] < b[0] + b[2] and b[0] < a[0] + a[2] and a[1] < b[1] + b[3] and b[1] < a[1] + a[3]
    assert occluded > 20 and overlapping > 20


def test_written_ground_truth_matches_the_scene(tmp_path):
    scene = make_road_scene(small("wide_distorted"), n_vehicles=8, seed=5, fps=6.0)
    paths = scene.write(tmp_path, video="video.avi")
    cap = cv2.VideoCapture(str(paths["video"]))
    assert int(cap.get(cv2.CAP_PROP_FRAME_COUNT)) == scene.n_frames
    ok, first = cap.read()
    assert ok and first.shape == (scene.setup.image_height, scene.setup.image_width, 3)
    assert np.abs(first.astype(int) - scene.frame(0)).mean() < 4.0  # Motion-JPEG is lossy
    gt = read_ground_truth(tmp_path)
    k = int(np.bincount(gt["boxes"][:, 0].astype(int)).argmax())  # the busiest frame (1-based)
    rows = gt["boxes"][gt["boxes"][:, 0] == k][:, 1:]
    assert np.allclose(rows, scene.boxes(k - 1), atol=1e-4)
    vehicles = gt["vehicles"]
    assert list(vehicles["vehicle_id"]) == [v.id for v in scene.vehicles]
    assert list(vehicles["class"]) == [v.cls for v in scene.vehicles]
    assert np.allclose(vehicles["L"], [v.L for v in scene.vehicles], atol=1e-4)
    for v, first_frame, last_frame in zip(scene.vehicles, vehicles["first_frame"], vehicles["last_frame"]):
        frames = gt["boxes"][gt["boxes"][:, 1] == v.id, 0]
        assert (first_frame, last_frame) == (frames.min(), frames.max())
    sil = gt["silhouettes"][(gt["silhouettes"][:, 0] == k)]
    for vid in np.unique(sil[:, 1]):
        poly = scene.silhouette(scene.vehicles[int(vid) - 1], k - 1)
        assert np.allclose(sil[sil[:, 1] == vid][:, 3:], poly, atol=1e-4)
    with open(paths["vehicles"]) as f:
        assert next(csv.reader(f))[:6] == ["vehicle_id", "class", "light_heavy", "W", "H", "L"]
    camera = json.loads(paths["camera"].read_text())
    assert set(camera) >= {"K", "dist", "R", "t", "road_axis_world", "image_size"}


def test_camera_file_is_read_by_vtrack_and_projects_like_opencv(tmp_path):
    from vtrack.synthetic_road import project

    for name in CAMERA_SETUPS:
        setup = small(name)
        path = tmp_path / f"{name}.json"
        path.write_text(json.dumps(setup.camera_file()))
        camera = vtrack.vehicles.read_camera_file(str(path))
        assert camera.image_size == (setup.image_width, setup.image_height)
        assert np.allclose(camera.centre, setup.centre())
        pts = np.array([[1.0, 30.0, 0.0], [6.0, 45.0, 1.5], [11.0, 60.0, 3.9]])
        assert np.allclose(camera.project(pts), project(setup, pts), atol=1e-9)


def test_bad_arguments():
    with pytest.raises(ValueError, match="setup must be"):
        make_road_scene("nowhere")
    with pytest.raises(ValueError, match="unknown classes"):
        make_road_scene(small("mast_low"), class_mix={"tractor": 1.0})
    with pytest.raises(ValueError, match="lane_speeds"):
        make_road_scene(small("mast_low"), lane_speeds=[20.0])
    scene = make_road_scene(small("mast_low"), n_vehicles=1, seed=0)
    with pytest.raises(IndexError):
        scene.frame(scene.n_frames)

"""The vehicle geometry's Python API (particle-filters-human-vehicle §3.1-3.2) against NumPy
transcriptions of the equations and against scenes rendered by vtrack.synthetic_road."""

import dataclasses
import json

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2")

import vtrack  # noqa: E402
from vtrack.synthetic_road import CAMERA_SETUPS, make_road_scene  # noqa: E402


def camera_of(setup):
    c = setup.camera_file()
    return vtrack.vehicles.Camera(c["K"], c["dist"], c["R"], c["t"], image_size=tuple(c["image_size"]))


def small(name, scale=3.0):
    s = CAMERA_SETUPS[name]
    return dataclasses.replace(s, image_width=int(s.image_width / scale), image_height=int(s.image_height / scale),
                               focal=s.focal / scale)


def line_foot(a, b, x):
    """NumPy: the foot of the perpendicular from each row of x to the line through a and b."""
    d = b - a
    return a + np.outer((x - a) @ d / (d @ d), d)


@pytest.fixture(scope="module")
def scenes():
    return {name: make_road_scene(small(name), n_vehicles=8, seed=11) for name in CAMERA_SETUPS}


def test_camera_round_trips_and_homography(tmp_path):
    setup = CAMERA_SETUPS["gantry"]
    cam = camera_of(setup)
    assert np.allclose(cam.centre, setup.centre())
    assert np.allclose(cam.road_axis, [0, 1, 0]) and np.allclose(cam.lateral_axis, [1, 0, 0])
    road = np.array([[0.0, 20.0], [7.0, 35.0], [13.0, 80.0]])
    px = cam.road_to_image(road)
    H = cam.road_to_image_homography
    u = np.column_stack([road, np.ones(3)]) @ H.T
    assert np.allclose(px, u[:, :2] / u[:, 2:], atol=1e-9)
    assert np.allclose(cam.image_to_road(px), road, atol=1e-9)
    assert np.allclose(H @ cam.image_to_road_homography, np.eye(3), atol=1e-9)
    d = cam.rays(px)
    world = np.column_stack([road, np.zeros(3)])
    v = world - cam.centre
    assert np.allclose(np.cross(v, d), 0.0, atol=1e-9)
    path = tmp_path / "camera.json"
    path.write_text(json.dumps(setup.camera_file()))
    assert np.allclose(vtrack.vehicles.read_camera_file(str(path)).R, cam.R)


def test_camera_bad_input():
    c = CAMERA_SETUPS["mast_low"].camera_file()
    with pytest.raises(TypeError, match="K"):
        vtrack.vehicles.Camera(np.array([["a"] * 3] * 3), c["dist"], c["R"], c["t"])
    with pytest.raises(ValueError, match="K must have shape"):
        vtrack.vehicles.Camera(np.eye(2), c["dist"], c["R"], c["t"])
    with pytest.raises(vtrack.InvalidArgument, match="R must be a rotation matrix"):
        vtrack.vehicles.Camera(c["K"], c["dist"], np.array(c["R"]) * 2, c["t"])
    with pytest.raises(vtrack.InvalidArgument, match="dist must have"):
        vtrack.vehicles.Camera(c["K"], [0.1, 0.2], c["R"], c["t"])
    cam = camera_of(CAMERA_SETUPS["mast_low"])
    with pytest.raises(ValueError, match=r"points must have shape \(N, 3\)"):
        cam.project(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="NaN"):
        cam.image_to_road(np.array([[np.nan, 1.0]]))
    with pytest.raises(vtrack.InvalidArgument, match="horizon"):
        cam.image_to_road(np.array([[480.0, 0.0]]))
    with pytest.raises(OSError):
        vtrack.vehicles.read_camera_file("/nonexistent/camera.json")


def test_projection_on_the_ray_is_the_papers_equation():
    cam = camera_of(CAMERA_SETUPS["mast_high"])
    obs = vtrack.vehicles.observe_vehicle(cam, [400.0, 250.0, 80.0, 60.0])
    a, b = obs.a, obs.b
    # L = a b^T - b a^T with homogeneous a, b.
    ah, bh = np.append(a, 1.0), np.append(b, 1.0)
    assert np.allclose(obs.plucker, np.outer(ah, bh) - np.outer(bh, ah))
    x = np.random.default_rng(0).normal([2.0, 2.0, 6.0], [1.0, 1.0, 3.0], size=(50, 3))
    y = line_foot(a, b, x)
    assert np.allclose(obs.project(x), y, atol=1e-9)
    assert np.allclose(obs.distance(x), np.linalg.norm(y - x, axis=1), atol=1e-9)
    s = np.array([0.2, 0.3, 0.5])
    expected = -0.5 * (((y - x) / s) ** 2).sum(axis=1)
    assert np.allclose(obs.log_likelihood(x, sigma_w=0.2, sigma_h=0.3, sigma_l=0.5), expected)
    with pytest.raises(vtrack.InvalidArgument, match="sigma_h"):
        obs.log_likelihood(x, sigma_h=-1.0)
    h0, h1 = obs.feasible_heights([0.4, 0.6, 1.0])
    assert h0 == pytest.approx(0.6) and h1 > h0
    assert np.allclose(obs.point_at_height(1.5), a + 1.5 / b[1] * (b - a))


def test_true_dimensions_lie_on_the_ray_of_exact_silhouettes(scenes):
    worst, n = 0.0, 0
    for name, scene in scenes.items():
        cam = camera_of(scene.setup)
        for k in range(0, scene.n_frames, 11):
            for v in scene.present(k):
                poly = scene.silhouette(v, k)
                if poly is None:
                    continue
                obs = vtrack.vehicles.observe_vehicle(cam, poly)
                worst = max(worst, obs.distance([[v.W, v.H, v.L]])[0])
                n += 1
                if not (obs.camera_within_width or obs.camera_within_length):
                    # X_0 is the footprint corner nearest the camera
                    corners = scene.corners(v, k)
                    assert np.linalg.norm(obs.to_whl(corners), axis=1).min() < 1e-3, name
    assert n > 100
    assert worst < 2e-3  # exact polygons (the distorted lens' hull is exact to ~0.01 px)


def test_rendered_silhouettes_give_rays_within_pixel_quantisation(scenes):
    for name, scene in scenes.items():
        cam = camera_of(scene.setup)
        for k in range(0, scene.n_frames, 13):
            for v in scene.present(k):
                if scene.silhouette(v, k) is None:
                    continue
                mask = scene.vehicle_mask(v, k).astype(np.uint8)
                contours, _ = cv2.findContours(mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
                contour = max(contours, key=len).reshape(-1, 2).astype(float)
                if len(contour) < 3:
                    continue
                obs = vtrack.vehicles.observe_vehicle(cam, contour)
                # One pixel at the far-most corner, on the road, bounds the error of the ray there.
                far = cam.road_to_image(obs.far_corner_world[None, :2])[0]
                step = cam.image_to_road(far + np.array([[0, 0], [1.5, 0], [0, 1.5], [-1.5, 0], [0, -1.5]]))
                tol = np.linalg.norm(step[1:] - step[0], axis=1).max() + 0.05
                assert obs.distance([[v.W, v.H, v.L]])[0] < tol, (name, k, v.id)


def test_box_observations_are_coarser_than_silhouettes(scenes):
    scene = scenes["mast_low"]
    cam = camera_of(scene.setup)
    k = scene.n_frames // 3
    for v in scene.present(k):
        poly = scene.silhouette(v, k)
        if poly is None:
            continue
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        box = vtrack.vehicles.observe_vehicle(cam, np.array([lo[0], lo[1], *(hi - lo)])).box
        sil = vtrack.vehicles.observe_vehicle(cam, poly).box
        assert box[0] <= sil[0] + 1e-9 and box[1] >= sil[1] - 1e-9
        assert box[2] <= sil[2] + 1e-9 and box[3] >= sil[3] - 1e-9
    with pytest.raises(ValueError, match=r"\(x, y, w, h\)"):
        vtrack.vehicles.observe_vehicle(cam, [1.0, 2.0, 3.0])
    with pytest.raises(vtrack.InvalidArgument, match="w, h > 0"):
        vtrack.vehicles.observe_vehicle(cam, [100.0, 120.0, -3.0, 4.0])


def test_class_prior_is_the_normalised_mixture():
    models = vtrack.vehicles.table1_vehicle_models()
    assert [m["name"] for m in models] == ["car", "motorbike", "truck", "trailer", "bus"]
    models[0]["weight"] = 4.0
    prior = vtrack.vehicles.VehicleModelPrior(models, min_size=[0.4, 0.6, 1.0])
    x = np.random.default_rng(1).normal([1.8, 2.0, 7.0], [0.3, 0.6, 3.0], size=(200, 3))
    x[0] = [0.3, 1.5, 4.0]
    mean = np.array([[m["W"], m["H"], m["L"]] for m in models])
    sigma = np.array([[m["sigma_w"], m["sigma_h"], m["sigma_l"]] for m in models])
    w = np.array([m["weight"] for m in models])
    w = w / w.sum()
    dens = w * np.exp(-0.5 * (((x[:, None, :] - mean) / sigma) ** 2).sum(-1)) / ((2 * np.pi) ** 1.5 * sigma.prod(1))
    got = prior.log_density(x)
    below = (x < [0.4, 0.6, 1.0]).any(axis=1)  # the truncation at min_size
    assert below[0] and below.sum() > 1 and (got[below] == -np.inf).all()
    ok = (dens[1:].sum(1) > 1e-300) & ~below[1:]
    assert np.allclose(got[1:][ok], np.log(dens[1:].sum(1))[ok])
    post = prior.class_log_posteriors(x)
    assert post.shape == (200, 5)
    assert np.allclose(np.exp(post).sum(1), 1.0)
    assert np.array_equal(prior.map_class(x)[1:][ok], dens[1:].argmax(1)[ok])
    assert prior.names == ["car", "motorbike", "truck", "trailer", "bus"]
    with pytest.raises(ValueError, match="unknown key 'heavvy'"):
        vtrack.vehicles.VehicleModelPrior([dict(models[0], heavvy=True)])
    with pytest.raises(vtrack.InvalidArgument, match="sigma_l must be a positive"):
        vtrack.vehicles.VehicleModelPrior([dict(models[0], sigma_l=0.0)])
    with pytest.raises(TypeError, match="models\\[0\\].W must be a number"):
        vtrack.vehicles.VehicleModelPrior([dict(models[0], W="wide")])


def test_models_file(tmp_path):
    path = tmp_path / "models.json"
    path.write_text(json.dumps({"models": [{"name": "car", "W": 1.8, "H": 1.5, "L": 4.5, "sigma_w": 0.1,
                                            "sigma_h": 0.15, "sigma_l": 0.5},
                                           {"name": "hgv", "W": 2.5, "H": 3.8, "L": 15, "sigma_w": 0.1,
                                            "sigma_h": 0.3, "sigma_l": 3, "heavy": True, "weight": 0.1}]}))
    models = vtrack.vehicles.read_vehicle_models_file(str(path))
    assert models[1] == {"name": "hgv", "W": 2.5, "H": 3.8, "L": 15.0, "sigma_w": 0.1, "sigma_h": 0.3,
                         "sigma_l": 3.0, "weight": 0.1, "heavy": True}
    assert vtrack.vehicles.VehicleModelPrior(models).models == models

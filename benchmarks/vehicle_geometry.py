"""The §3.1 observation geometry of particle-filters-human-vehicle on synthetic road views.

Usage: python benchmarks/vehicle_geometry.py [--vehicles N] [--seed S] [--step K]

For every camera set-up of vtrack.synthetic_road (full resolution) it generates a scene of N
vehicles and, every K-th frame, observes each vehicle that is fully in view with
vtrack.vehicles.observe_vehicle from:
  * exact: the exact silhouette polygon (the generator's projected cuboid outline);
  * noisy s: that polygon (its ~190 outline samples) with independent Gaussian noise of s pixels
    on every point (s = 0.5, 1, 2, 4): boundary jitter, which also biases the box's extremes
    outwards;
  * mask: the outer contour of the rendered pixels (ray casting, pixel quantisation);
  * box: the image bounding box of the rendered pixels (x = i0 - 0.5, w = i1 - i0 + 1).
Table 1 reports the distance |y - x| of the true (W, H, L) from the observation's ray (metres)
-- the miss of the likelihood's ridge: the ray likelihood exp(-d^2 / (2 sigma^2)) peaks at the
truth exactly when d = 0 -- as median / 90th percentile, and the share within 1 and 2 sigma of
the default sigma = 0.25 m; and, for the views where the camera's foot is outside the box
(the paper's construction), the pixel distance between the image of the cuboid's top far corner
and the box's far-most corner.
Table 2 goes beyond one frame: a vehicle's rays from all its frames, in its own W-H-L frame,
meet near (W, H, L); the least-squares point of the rays (minimising the summed squared
distances) is reported against the truth (mean absolute error of W, H, L, metres) per
observation type -- the "combine the rays of all a vehicle's frames" extension of issue 13.
"""

import argparse
import os
import sys
from collections import defaultdict

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _table import print_table  # noqa: E402

import cv2  # noqa: E402

import vtrack  # noqa: E402
from vtrack.synthetic_road import CAMERA_SETUPS, make_road_scene  # noqa: E402

SIGMA = 0.25  # RayLikelihoodParams' default
NOISE_PX = (0.5, 1.0, 2.0, 4.0)


def camera_of(setup):
    c = setup.camera_file()
    return vtrack.vehicles.Camera(c["K"], c["dist"], c["R"], c["t"], image_size=tuple(c["image_size"]))


def observations(scene, v, k, rng):
    """{type: silhouette (polygon or box)} for vehicle v at frame k (fully in view)."""
    poly = scene.silhouette(v, k)
    mask = scene.vehicle_mask(v, k)
    contours, _ = cv2.findContours(mask.astype(np.uint8), cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    contour = max(contours, key=len).reshape(-1, 2).astype(float)
    ys, xs = np.nonzero(mask)
    out = {"exact": poly, "mask": contour if len(contour) >= 3 else None,
           "box": np.array([xs.min() - 0.5, ys.min() - 0.5, xs.max() - xs.min() + 1.0, ys.max() - ys.min() + 1.0])}
    for s in NOISE_PX:
        out[f"noisy {s:g} px"] = poly + rng.normal(0.0, s, poly.shape)
    return out


def least_squares_point(a, d):
    """The point minimising the summed squared distances to the lines a_i + t d_i."""
    d = d / np.linalg.norm(d, axis=1, keepdims=True)
    P = np.eye(3)[None] - d[:, :, None] * d[:, None, :]
    return np.linalg.solve(P.sum(0), np.einsum("nij,nj->i", P, a))


def measure(name, n_vehicles, seed, step):
    setup = CAMERA_SETUPS[name]
    scene = make_road_scene(setup, n_vehicles=n_vehicles, seed=seed)
    cam = camera_of(setup)
    rng = np.random.default_rng(seed)
    dist = defaultdict(list)
    corner_px = []
    rays = defaultdict(lambda: defaultdict(list))  # type -> vehicle id -> [(a, b)]
    for k in range(0, scene.n_frames, step):
        for v in scene.present(k):
            if scene.silhouette(v, k) is None:
                continue
            truth = np.array([[v.W, v.H, v.L]])
            for kind, sil in observations(scene, v, k, rng).items():
                if sil is None:
                    continue
                try:
                    obs = vtrack.vehicles.observe_vehicle(cam, sil)
                except vtrack.InvalidArgument:  # a noisy vertex above the horizon
                    continue
                dist[kind].append(obs.distance(truth)[0])
                rays[kind][v.id].append((obs.a, obs.b - obs.a))
                if kind == "mask" and not (obs.camera_within_width or obs.camera_within_length):
                    whl = obs.to_whl(scene.corners(v, k))
                    top_far = whl[:, 0] + whl[:, 2] + 10 * whl[:, 1]
                    far_px = cam.road_to_image(obs.far_corner_world[None, :2])[0]
                    corner_px.append(np.linalg.norm(cam.project(scene.corners(v, k)[[top_far.argmax()]])[0] - far_px))
    multi = {}
    for kind, per_vehicle in rays.items():
        errors = []
        for vid, lines in per_vehicle.items():
            if len(lines) < 2:
                continue
            a = np.array([l[0] for l in lines])
            d = np.array([l[1] for l in lines])
            v = scene.vehicles[vid - 1]
            errors.append(np.abs(least_squares_point(a, d) - [v.W, v.H, v.L]))
        multi[kind] = np.array(errors)
    return dist, corner_px, multi


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--vehicles", type=int, default=30)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--step", type=int, default=6, help="observe every STEP-th frame")
    args = parser.parse_args()
    rows1, rows2 = [], []
    for name in CAMERA_SETUPS:
        dist, corner_px, multi = measure(name, args.vehicles, args.seed, args.step)
        for kind, d in dist.items():
            d = np.asarray(d)
            px = (f"{np.median(corner_px):.2f} / {np.percentile(corner_px, 90):.2f}" if kind == "mask" and corner_px
                  else "")
            rows1.append((name, kind, len(d), f"{np.median(d):.3f} / {np.percentile(d, 90):.3f}",
                          f"{np.mean(d < SIGMA):.2f}", f"{np.mean(d < 2 * SIGMA):.2f}", px))
        for kind, e in multi.items():
            if len(e):
                rows2.append((name, kind, len(e), *(f"{x:.3f}" for x in e.mean(axis=0))))
    print(f"Table 1: distance of the true (W, H, L) from the ray, {args.vehicles} vehicles per set-up, "
          f"seed {args.seed}, every {args.step}th frame\n")
    print_table(["set-up", "observation", "views", "median / p90 (m)", "< 1 sigma", "< 2 sigma",
                 "top-far corner px, median / p90"], rows1)
    print("\nTable 2: least-squares intersection of each vehicle's rays over its frames, mean |error| (m)\n")
    print_table(["set-up", "observation", "vehicles", "W", "H", "L"], rows2)


if __name__ == "__main__":
    main()

"""Synthetic road scenes with exact ground truth, for vehicle dimension estimation.

particle-filters-human-vehicle §3 estimates a vehicle's width, height and length (a cuboid with
yaw 0 along the road) from its silhouettes in a calibrated road camera. :func:`make_road_scene`
draws, from a seed, a camera over a multi-lane road and a stream of vehicles of realistic, varied
dimensions (:data:`VEHICLE_CLASSES`), and renders them as shaded cuboids over a textured road by
ray casting every pixel (exact occlusion and exact lens distortion). Ground truth: every
vehicle's class, light/heavy category and dimensions, and per frame its image box, its full
silhouette polygon and how much of it is visible. ``scene.write(folder)`` saves a video, the
camera file (the format of :func:`vtrack.vehicles.read_camera_file`) and CSV ground truth.

World coordinates (metres): Z up, the road is Z = 0, the road axis is +Y (the camera file's
``road_axis_world``), lanes of ``lane_width`` side by side from X = 0 to X = n_lanes *
lane_width. Lanes in the left half (small X) carry traffic towards -Y, the right half towards +Y.
Every vehicle of a lane drives at that lane's speed, so vehicles never collide; they enter and
leave the simulated stretch of road (the part the camera sees plus a margin), so each passes
through the view once. Image coordinates are continuous with pixel centres at integers
(OpenCV's); a pixel belongs to a vehicle when the ray through its centre hits the cuboid.

The projections and rays use OpenCV (``cv2.projectPoints``, ``cv2.undistortPoints``) directly,
not vtrack's C++ camera, so the tests of the one check the other.
"""

from __future__ import annotations

import csv
import json
import math
import os
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

# Per class: light/heavy, ranges (metres) of W, H, L drawn uniformly and independently, and the
# default share of the traffic. Sources for the ranges: EU Directive 96/53/EC limits for heavy
# vehicles (width 2.55 m, height 4 m where limited, rigid 12 m, articulated 16.5 m, road train
# 18.75 m, 2-axle bus 13.5 m) and typical dimensions of current models for the others (small car
# to large SUV; Transit/Sprinter-type vans of at most 3.5 t, which are light; a motorbike with its
# rider; a car towing a trailer, bounded by one cuboid). Table 1 of the paper gives only means;
# these ranges are deliberately wider than its sigmas and put vans between cars and trucks.
VEHICLE_CLASSES: Dict[str, dict] = {
    "car": {"heavy": False, "W": (1.65, 1.95), "H": (1.35, 1.80), "L": (3.6, 5.0), "share": 0.68},
    "van": {"heavy": False, "W": (1.90, 2.10), "H": (1.90, 2.80), "L": (4.8, 7.0), "share": 0.08},
    "motorbike": {"heavy": False, "W": (0.70, 0.95), "H": (1.20, 1.60), "L": (1.9, 2.4), "share": 0.04},
    "car_trailer": {"heavy": False, "W": (1.70, 2.00), "H": (1.40, 1.90), "L": (6.5, 9.5), "share": 0.03},
    "truck": {"heavy": True, "W": (2.40, 2.55), "H": (2.90, 4.00), "L": (7.0, 12.0), "share": 0.08},
    "articulated": {"heavy": True, "W": (2.50, 2.55), "H": (3.60, 4.00), "L": (13.5, 18.75), "share": 0.05},
    "bus": {"heavy": True, "W": (2.50, 2.55), "H": (3.00, 3.40), "L": (10.5, 13.5), "share": 0.04},
}


@dataclass(frozen=True)
class CameraSetup:
    """A road camera: optical centre at (lateral, along, height) metres, heading `yaw` degrees
    from +Y towards +X, looking `pitch` degrees below the horizon, no roll; a pinhole of focal
    length `focal` pixels, principal point at the image centre, OpenCV distortion `dist`."""

    height: float = 8.0
    pitch: float = 15.0
    yaw: float = 10.0
    lateral: float = -3.0
    along: float = 0.0
    focal: float = 900.0
    image_width: int = 960
    image_height: int = 540
    dist: Tuple[float, ...] = ()

    def rotation(self) -> np.ndarray:
        """World -> camera rotation R (rows: right, down, forward)."""
        yaw, pitch = math.radians(self.yaw), math.radians(self.pitch)
        forward = np.array([math.sin(yaw) * math.cos(pitch), math.cos(yaw) * math.cos(pitch), -math.sin(pitch)])
        right = np.cross(forward, [0.0, 0.0, 1.0])
        right /= np.linalg.norm(right)
        down = np.cross(forward, right)
        return np.stack([right, down, forward])

    def centre(self) -> np.ndarray:
        return np.array([self.lateral, self.along, self.height], float)

    def K(self) -> np.ndarray:
        return np.array([[self.focal, 0.0, (self.image_width - 1) / 2.0],
                         [0.0, self.focal, (self.image_height - 1) / 2.0], [0.0, 0.0, 1.0]])

    def camera_file(self) -> dict:
        """The camera file's content (vtrack.vehicles.read_camera_file); `setup` is ignored by readers."""
        R = self.rotation()
        return {"K": self.K().tolist(), "dist": list(self.dist), "R": R.tolist(),
                "t": (-R @ self.centre()).tolist(), "road_axis_world": [0.0, 1.0, 0.0],
                "image_size": [self.image_width, self.image_height], "setup": asdict(self)}


# Camera set-ups of different heights, pitches, yaws and lenses, over the default 4-lane road
# (X 0..14 m): roadside masts, a gantry above lane 2 (X = 5.25), a side view, a wide-angle lens
# with barrel distortion.
CAMERA_SETUPS: Dict[str, CameraSetup] = {
    "mast_low": CameraSetup(height=6.0, pitch=12.0, yaw=14.0, lateral=-2.5),
    "mast_high": CameraSetup(height=12.0, pitch=22.0, yaw=8.0, lateral=-3.0),
    "gantry": CameraSetup(height=7.5, pitch=16.0, yaw=0.0, lateral=5.25),
    "side": CameraSetup(height=10.0, pitch=20.0, yaw=38.0, lateral=-9.0),
    "wide_distorted": CameraSetup(height=9.0, pitch=20.0, yaw=10.0, lateral=-3.0, focal=560.0,
                                  dist=(-0.30, 0.09, 0.0005, -0.0005, -0.012)),
}


@dataclass
class RoadVehicle:
    id: int                  # 1, 2, ... in order of entry
    cls: str                 # a key of VEHICLE_CLASSES
    heavy: bool
    W: float
    H: float
    L: float
    lane: int                # 0 .. n_lanes - 1
    direction: int           # +1: travels +Y, -1: travels -Y
    speed: float             # m/s
    x0: float                # lateral coordinate of the footprint's left side (X), metres
    enter: float             # time (s) at which it enters the simulated stretch
    colour: np.ndarray = field(repr=False, default=None)

    def y0(self, time: float, y_range: Tuple[float, float]) -> float:
        """Rear (smallest Y) of the footprint at `time`."""
        s = self.speed * (time - self.enter)
        return y_range[0] - self.L + s if self.direction > 0 else y_range[1] - s

    def corners(self, time: float, y_range: Tuple[float, float]) -> np.ndarray:
        """(8, 3) world corners; corner i has bits (w, l, h) = (i & 1, i & 2, i & 4)."""
        i = np.arange(8)
        return np.stack([self.x0 + self.W * (i & 1 > 0), self.y0(time, y_range) + self.L * (i & 2 > 0),
                         self.H * (i & 4 > 0)], axis=1).astype(float)


# The 12 edges of a cuboid whose corner i has bits (w, l, h) = (i & 1, i & 2, i & 4).
_EDGES = [(a, a | b) for a in range(8) for b in (1, 2, 4) if not a & b]


def _contour_loop(corners: np.ndarray, centre: np.ndarray) -> List[int]:
    """The corners (indices) of a cuboid's silhouette loop seen from `centre`, in order: the
    edges whose two faces are one turned towards the centre and one away, chained."""
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    # Face (axis, side) faces the centre when the centre lies beyond its plane.
    front = {(a, 0): centre[a] < lo[a] for a in range(3)}
    front.update({(a, 1): centre[a] > hi[a] for a in range(3)})
    neighbours: Dict[int, List[int]] = {}
    for i, j in _EDGES:
        bit = (i ^ j).bit_length() - 1  # the axis the edge runs along
        faces = [(a, (i >> a) & 1) for a in range(3) if a != bit]
        if front[faces[0]] != front[faces[1]]:
            neighbours.setdefault(i, []).append(j)
            neighbours.setdefault(j, []).append(i)
    loop = [min(neighbours)]
    while True:
        nxt = [n for n in neighbours[loop[-1]] if len(loop) < 2 or n != loop[-2]][0]
        if nxt == loop[0]:
            return loop
        loop.append(nxt)


def _undistort_normalised(pixels: np.ndarray, K: np.ndarray, dist: Sequence[float]) -> np.ndarray:
    """(N, 2) image pixels -> normalised pinhole coordinates (N, 2), iterated to convergence."""
    import cv2

    src = np.ascontiguousarray(pixels, np.float64).reshape(-1, 1, 2)
    d = np.asarray(dist, np.float64)
    if d.size == 0 or not d.any():
        return (pixels - K[:2, 2]) / np.diag(K)[:2]
    criteria = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 100, 1e-12)
    if hasattr(cv2, "undistortPointsIter"):  # OpenCV 4.x names the overload with criteria so
        out = cv2.undistortPointsIter(src, K, d, None, None, criteria)
    else:
        out = cv2.undistortPoints(src, K, d, criteria=criteria)
    return out.reshape(-1, 2)


def project(setup: CameraSetup, points: np.ndarray) -> np.ndarray:
    """World points (N, 3) -> image pixels (N, 2) by cv2.projectPoints; NaN at or behind the
    camera's focal plane."""
    import cv2

    R = setup.rotation()
    t = -R @ setup.centre()
    pts = np.ascontiguousarray(points, np.float64).reshape(-1, 3)
    px, _ = cv2.projectPoints(pts, cv2.Rodrigues(R)[0], t, setup.K(), np.asarray(setup.dist, np.float64))
    px = px.reshape(-1, 2)
    px[(pts @ R[2] + t[2]) <= 0] = np.nan
    return px


def _value_noise(x: np.ndarray, y: np.ndarray, cell: float, seed: int) -> np.ndarray:
    """Smooth deterministic noise in [-1, 1] of road coordinates: bilinear interpolation of
    hashed values on a grid of `cell` metres."""
    gx, gy = x / cell, y / cell
    ix, iy = np.floor(gx), np.floor(gy)
    fx, fy = gx - ix, gy - iy

    def h(a, b):
        v = (a.astype(np.int64) * 73856093) ^ (b.astype(np.int64) * 19349663) ^ (seed * 83492791)
        v = (v ^ (v >> 13)) * 1274126177
        return ((v ^ (v >> 16)) & 0xFFFF) / 32767.5 - 1.0

    return ((h(ix, iy) * (1 - fx) + h(ix + 1, iy) * fx) * (1 - fy)
            + (h(ix, iy + 1) * (1 - fx) + h(ix + 1, iy + 1) * fx) * fy)


@dataclass
class RoadScene:
    """A rendered road scene; build it with :func:`make_road_scene`."""

    setup: CameraSetup
    vehicles: List[RoadVehicle]
    n_frames: int
    fps: float
    n_lanes: int
    lane_width: float
    y_range: Tuple[float, float]
    seed: int
    noise_std: float = 2.0
    _rays: np.ndarray = field(default=None, repr=False)        # H x W x 3 world directions
    _background: np.ndarray = field(default=None, repr=False)  # H x W x 3 float32 BGR
    _fov: Tuple[np.ndarray, np.ndarray] = field(default=None, repr=False)  # normalised image bbox

    def __len__(self) -> int:
        return self.n_frames

    @property
    def image_size(self) -> Tuple[int, int]:
        return self.setup.image_width, self.setup.image_height

    def time(self, k: int) -> float:
        return k / self.fps

    def corners(self, v: RoadVehicle, k: int) -> np.ndarray:
        """(8, 3) world corners of vehicle v at frame k (0-based)."""
        return v.corners(self.time(k), self.y_range)

    def present(self, k: int) -> List[RoadVehicle]:
        """The vehicles on the simulated stretch at frame k."""
        t = self.time(k)
        out = []
        for v in self.vehicles:
            y0 = v.y0(t, self.y_range)
            if y0 + v.L > self.y_range[0] - 1.0 and y0 < self.y_range[1] + 1.0 and t >= v.enter:
                out.append(v)
        return out

    # ---- rendering -------------------------------------------------------------------------------

    def _candidate_region(self, corners: np.ndarray) -> Optional[Tuple[int, int, int, int]]:
        """Pixel rows/columns (y0, y1, x0, x1) that may see the cuboid, or None if none can: the
        cuboid clipped to the space in front of the camera, its pinhole (normalised) bounding
        box clipped to the field of view's, that box's outline distorted into the image. The
        distortion model is only ever applied inside the field of view, where it is monotonic
        (outside it the polynomial can fold far-away points back into the image)."""
        import cv2

        R = self.setup.rotation()
        cam = (corners - self.setup.centre()) @ R.T
        near = 1e-3
        pts = [cam[i] for i in range(8) if cam[i, 2] > near]
        for a, b in _EDGES:
            za, zb = cam[a, 2] - near, cam[b, 2] - near
            if za * zb < 0:
                pts.append(cam[a] + za / (za - zb) * (cam[b] - cam[a]))
        if not pts:
            return None
        pts = np.asarray(pts)
        n = pts[:, :2] / pts[:, 2:]
        lo, hi = np.maximum(n.min(axis=0), self._fov[0]), np.minimum(n.max(axis=0), self._fov[1])
        if (hi <= lo).any():
            return None
        u = np.linspace(0.0, 1.0, 17)
        outline = np.concatenate([np.column_stack([lo[0] + (hi[0] - lo[0]) * u, np.full(17, y)]) for y in (lo[1], hi[1])]
                                 + [np.column_stack([np.full(17, x), lo[1] + (hi[1] - lo[1]) * u]) for x in (lo[0], hi[0])])
        px, _ = cv2.projectPoints(np.column_stack([outline, np.ones(len(outline))]), np.zeros(3), np.zeros(3),
                                  self.setup.K(), np.asarray(self.setup.dist, np.float64))
        px = px.reshape(-1, 2)
        w, h = self.image_size
        x0, y0 = np.maximum(np.floor(px.min(axis=0)).astype(int) - 2, 0)
        x1, y1 = np.minimum(np.ceil(px.max(axis=0)).astype(int) + 3, [w, h])
        return (y0, y1, x0, x1) if x1 > x0 and y1 > y0 else None

    def _cast(self, v: RoadVehicle, k: int):
        """Ray-box intersection (slab method) over the vehicle's candidate pixels: (region, hit
        mask, ray parameter of the entry point, entry face axis 0/1/2, entry face sign +-1)."""
        corners = self.corners(v, k)
        region = self._candidate_region(corners)
        if region is None:
            return None
        y0, y1, x0, x1 = region
        d = self._rays[y0:y1, x0:x1]  # no zero components (see _pixel_rays): no 0/0
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        c = self.setup.centre()
        t1 = (lo - c) / d
        t2 = (hi - c) / d
        near, far = np.minimum(t1, t2), np.maximum(t1, t2)
        t_in, t_out = near.max(axis=2), far.min(axis=2)
        hit = (t_in <= t_out) & (t_in > 0)
        axis = near.argmax(axis=2)
        sign = -np.sign(np.take_along_axis(d, axis[..., None], axis=2)[..., 0])  # outward normal
        return region, hit, t_in, axis, sign

    def _shade(self, v: RoadVehicle, hit_z: np.ndarray, axis: np.ndarray, sign: np.ndarray) -> np.ndarray:
        """BGR colour (n, 3) of hit points: Lambertian faces under a fixed sun plus ambient light,
        dark windows in a band of the side faces of light vehicles and buses."""
        normal = np.zeros((axis.size, 3))
        normal[np.arange(axis.size), axis] = sign
        sun = np.array([0.45, -0.35, 0.82])
        shade = 0.38 + 0.62 * np.clip(normal @ (sun / np.linalg.norm(sun)), 0.0, 1.0)
        colour = v.colour[None, :] * shade[:, None]
        if v.cls not in ("truck", "articulated"):
            rel = hit_z / v.H
            window = (axis != 2) & (rel > 0.55) & (rel < 0.88)
            colour[window] = np.array([55.0, 45.0, 40.0]) * shade[window, None]
        return colour

    def _casts(self, k: int) -> Dict[int, tuple]:
        """Vehicle id -> (vehicle, _cast result) for the vehicles that may be seen at frame k."""
        if not 0 <= k < self.n_frames:
            raise IndexError(f"frame index {k} out of range [0, {self.n_frames})")
        out = {}
        for v in self.present(k):
            cast = self._cast(v, k)
            if cast is not None and cast[1].any():
                out[v.id] = (v, cast)
        return out

    def _compose(self, k: int, casts: Dict[int, tuple]) -> Tuple[np.ndarray, np.ndarray]:
        """Frame k from its casts: nearest hit per pixel (z-buffer), shaded, plus sensor noise."""
        w, h = self.image_size
        img = self._background.copy()
        depth = np.full((h, w), np.inf)
        ids = np.zeros((h, w), np.int32)
        for v, ((y0, y1, x0, x1), hit, t_in, axis, sign) in casts.values():
            closer = hit & (t_in < depth[y0:y1, x0:x1])
            if not closer.any():
                continue
            depth[y0:y1, x0:x1][closer] = t_in[closer]
            ids[y0:y1, x0:x1][closer] = v.id
            hit_z = self.setup.height + t_in[closer] * self._rays[y0:y1, x0:x1, 2][closer]
            img[y0:y1, x0:x1][closer] = self._shade(v, hit_z, axis[closer], sign[closer])
        rng = np.random.default_rng([self.seed, k])
        img += rng.standard_normal(img.shape, dtype=np.float32) * np.float32(self.noise_std)
        return np.clip(img + 0.5, 0, 255).astype(np.uint8), ids

    def render(self, k: int) -> Tuple[np.ndarray, np.ndarray]:
        """Frame k (0-based): (H x W x 3 uint8 BGR image, H x W int32 map of the visible vehicle's
        id per pixel, 0 for road)."""
        return self._compose(k, self._casts(k))

    def frame(self, k: int) -> np.ndarray:
        """H x W x 3 uint8 BGR frame k (0-based)."""
        return self.render(k)[0]

    def vehicle_mask(self, v: RoadVehicle, k: int) -> np.ndarray:
        """H x W bool: the pixels whose ray hits vehicle v at frame k, ignoring other vehicles."""
        w, h = self.image_size
        mask = np.zeros((h, w), bool)
        cast = self._cast(v, k)
        if cast is not None:
            (y0, y1, x0, x1), hit = cast[0], cast[1]
            mask[y0:y1, x0:x1] = hit
        return mask

    # ---- ground truth ----------------------------------------------------------------------------

    def silhouette(self, v: RoadVehicle, k: int, samples: int = 32) -> Optional[np.ndarray]:
        """The vehicle's full silhouette at frame k as an image polygon (N, 2): its contour edges
        (those between a face turned towards the camera and one turned away), chained into a
        loop, each sampled at `samples` points and projected with cv2.projectPoints. Exact up
        to the chords between samples, also under lens distortion, where the outline bends (and
        may be concave, so it is not the convex hull of the projected corners). None unless the
        whole cuboid is in front of the camera and inside the image (a vehicle never fully in
        view has no complete silhouette)."""
        corners = self.corners(v, k)
        loop = _contour_loop(corners, self.setup.centre())
        u = np.linspace(0.0, 1.0, samples, endpoint=False)[:, None]
        pts = np.concatenate([corners[a] * (1 - u) + corners[b] * u for a, b in zip(loop, loop[1:] + loop[:1])])
        px = project(self.setup, pts)
        w, h = self.image_size
        if not np.isfinite(px).all() or px.min() < -0.5 or (px[:, 0] > w - 0.5).any() or (px[:, 1] > h - 0.5).any():
            return None
        return px

    def frame_with_truth(self, k: int) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(frame, id map, boxes(k)) from one rendering of frame k."""
        casts = self._casts(k)
        img, ids = self._compose(k, casts)
        return img, ids, self._boxes(k, casts, ids)

    def boxes(self, k: int) -> np.ndarray:
        """Ground-truth rows of frame k, one per vehicle with a visible pixel, in id order:
        (id, x, y, w, h, in_view, visible). For a vehicle fully in view (in_view = 1) the box is
        its silhouette's exact extent [x, x + w] x [y, y + h] in continuous pixel coordinates;
        otherwise the extent of its pixels inside the image (pixel i covers [i - 0.5, i + 0.5]).
        visible = the share of its pixels (ignoring the others) not hidden by a nearer vehicle."""
        return self.frame_with_truth(k)[2]

    def _boxes(self, k: int, casts: Dict[int, tuple], ids: np.ndarray) -> np.ndarray:
        rows = []
        for vid in sorted(casts):
            v, ((y0, y1, x0, x1), hit, *_) = casts[vid]
            visible = float((ids[y0:y1, x0:x1][hit] == vid).sum()) / int(hit.sum())
            poly = self.silhouette(v, k)
            if poly is not None:
                (bx0, by0), (bx1, by1) = poly.min(axis=0), poly.max(axis=0)
            else:
                ys, xs = np.nonzero(hit)
                bx0, by0, bx1, by1 = x0 + xs.min() - 0.5, y0 + ys.min() - 0.5, x0 + xs.max() + 0.5, y0 + ys.max() + 0.5
            rows.append((vid, bx0, by0, bx1 - bx0, by1 - by0, float(poly is not None), visible))
        return np.asarray(rows, np.float64).reshape(-1, 7)

    def camera_file(self) -> dict:
        return self.setup.camera_file()

    def with_vehicles(self, vehicles: Sequence[RoadVehicle]) -> RoadScene:
        """The same road and camera with hand-placed `vehicles` (ids 1, 2, ... in entry order,
        lanes of this scene's width), lasting until the last of them has left the stretch."""
        out = RoadScene(self.setup, list(vehicles), _frames_to_clear(vehicles, self.y_range, self.fps), self.fps,
                        self.n_lanes, self.lane_width, self.y_range, self.seed, self.noise_std)
        out._rays, out._fov, out._background = self._rays, self._fov, self._background
        return out

    def write(self, folder: Union[str, os.PathLike], video: str = "video.avi") -> Dict[str, Path]:
        """Writes `video` (.avi: Motion-JPEG, .mp4: MPEG-4, .mkv: lossless FFV1), camera.json,
        vehicles.csv (id, class, light_heavy, W, H, L, lane, direction, speed, first_frame,
        last_frame, frames_in_view; frames from 1, first/last = frames with a visible pixel),
        boxes.csv (frame, vehicle_id, x, y, w, h, in_view, visible) and silhouettes.csv (frame,
        vehicle_id, vertex, x, y; vehicles fully in view only). Returns their paths."""
        import cv2

        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        paths = {"video": out / video, "camera": out / "camera.json", "vehicles": out / "vehicles.csv",
                 "boxes": out / "boxes.csv", "silhouettes": out / "silhouettes.csv"}
        fourcc = {".avi": "MJPG", ".mp4": "mp4v", ".mkv": "FFV1"}.get(paths["video"].suffix.lower())
        if fourcc is None:
            raise ValueError(f"video must end in .avi, .mp4 or .mkv, got {video!r}")
        writer = cv2.VideoWriter(str(paths["video"]), cv2.VideoWriter_fourcc(*fourcc), self.fps, self.image_size)
        if not writer.isOpened():
            raise OSError(f"cannot write video {paths['video']}")
        seen: Dict[int, List[int]] = {}
        with open(paths["boxes"], "w", newline="") as fb, open(paths["silhouettes"], "w", newline="") as fs:
            boxes, sil = csv.writer(fb), csv.writer(fs)
            boxes.writerow(["frame", "vehicle_id", "x", "y", "w", "h", "in_view", "visible"])
            sil.writerow(["frame", "vehicle_id", "vertex", "x", "y"])
            for k in range(self.n_frames):
                img, _, rows = self.frame_with_truth(k)
                writer.write(img)
                by_id = {v.id: v for v in self.present(k)}
                for vid, x, y, w, h, in_view, visible in rows:
                    vid = int(vid)
                    seen.setdefault(vid, []).append(k + 1 if in_view else -(k + 1))
                    boxes.writerow([k + 1, vid, f"{x:.4f}", f"{y:.4f}", f"{w:.4f}", f"{h:.4f}", int(in_view),
                                    f"{visible:.4f}"])
                    if in_view:
                        for i, (px, py) in enumerate(self.silhouette(by_id[vid], k)):
                            sil.writerow([k + 1, vid, i, f"{px:.4f}", f"{py:.4f}"])
        writer.release()
        paths["camera"].write_text(json.dumps(self.camera_file(), indent=1))
        with open(paths["vehicles"], "w", newline="") as f:
            rows = csv.writer(f)
            rows.writerow(["vehicle_id", "class", "light_heavy", "W", "H", "L", "lane", "direction", "speed",
                           "first_frame", "last_frame", "frames_in_view"])
            for v in self.vehicles:
                frames = [abs(s) for s in seen.get(v.id, [])]
                rows.writerow([v.id, v.cls, "heavy" if v.heavy else "light", f"{v.W:.4f}", f"{v.H:.4f}",
                               f"{v.L:.4f}", v.lane, v.direction, f"{v.speed:.3f}",
                               min(frames, default=0), max(frames, default=0),
                               sum(1 for s in seen.get(v.id, []) if s > 0)])
        return paths


def _visible_along_range(setup: CameraSetup) -> Tuple[float, float]:
    """The Y range of the road (Z = 0) seen by the image border's pixels below the horizon,
    clipped to [-60, 160] m (farther vehicles are a few pixels)."""
    w, h = setup.image_width, setup.image_height
    border = np.concatenate([np.stack([np.linspace(0, w - 1, 64), np.full(64, y)], 1) for y in (0, h - 1)]
                            + [np.stack([np.full(64, x), np.linspace(0, h - 1, 64)], 1) for x in (0, w - 1)])
    n = _undistort_normalised(border, setup.K(), setup.dist)
    d = np.column_stack([n, np.ones(len(n))]) @ setup.rotation()  # world directions (R^T d_cam)
    below = d[:, 2] < -1e-6
    y = setup.along + setup.height * d[below, 1] / -d[below, 2]
    lo, hi = (y.min(), y.max()) if below.any() else (0.0, 0.0)
    if (~below).any():
        hi = 160.0  # the horizon is in view
    return max(lo, -60.0), min(hi, 160.0)


def _draw_vehicles(rng: np.random.Generator, n: int, class_mix: Dict[str, float]) -> List[Tuple[str, float, float, float]]:
    names = list(class_mix)
    p = np.array([class_mix[c] for c in names], float)
    classes = rng.choice(len(names), size=n, p=p / p.sum())
    out = []
    for c in classes:
        spec = VEHICLE_CLASSES[names[c]]
        W, H, L = (rng.uniform(*spec[k]) for k in ("W", "H", "L"))
        out.append((names[c], W, H, L))
    return out


def make_road_scene(setup: Union[str, CameraSetup] = "mast_high", n_vehicles: int = 40, seed: int = 0, *,
                    fps: float = 25.0, n_lanes: int = 4, lane_width: float = 3.5,
                    lane_speeds: Optional[Sequence[float]] = None, mean_gap: float = 2.5, min_gap: float = 0.8,
                    class_mix: Optional[Dict[str, float]] = None, noise_std: float = 2.0) -> RoadScene:
    """A seeded road scene: `n_vehicles` vehicles in `n_lanes` lanes seen by `setup` (a
    CameraSetup or a name in CAMERA_SETUPS). Each lane has its own speed (`lane_speeds` m/s,
    default drawn from 20-32 m/s); a lane's vehicles follow each other with a time gap of
    `min_gap` + Exponential(`mean_gap`) seconds between one's rear and the next one's front.
    `class_mix` maps VEHICLE_CLASSES names to shares (default: their `share`). The scene lasts
    until the last vehicle has left the stretch of road the camera sees."""
    if isinstance(setup, str):
        if setup not in CAMERA_SETUPS:
            raise ValueError(f"setup must be a CameraSetup or one of {sorted(CAMERA_SETUPS)}, got {setup!r}")
        setup = CAMERA_SETUPS[setup]
    if n_vehicles < 1 or n_lanes < 1 or not fps > 0 or not lane_width > 0:
        raise ValueError("n_vehicles, n_lanes, fps and lane_width must be positive")
    mix = dict(class_mix) if class_mix is not None else {c: s["share"] for c, s in VEHICLE_CLASSES.items()}
    unknown = set(mix) - set(VEHICLE_CLASSES)
    if unknown:
        raise ValueError(f"class_mix has unknown classes {sorted(unknown)}; known: {sorted(VEHICLE_CLASSES)}")
    rng = np.random.default_rng(seed)
    speeds = np.asarray(lane_speeds if lane_speeds is not None else rng.uniform(20.0, 32.0, n_lanes), float)
    if speeds.shape != (n_lanes,) or not (speeds > 0).all():
        raise ValueError(f"lane_speeds must be {n_lanes} positive speeds (m/s)")
    lo, hi = _visible_along_range(setup)
    y_range = (lo - 25.0, hi + 25.0)
    next_free = rng.uniform(0.0, 2.0, n_lanes)  # earliest entry time per lane
    vehicles = []
    for i, (cls, W, H, L) in enumerate(_draw_vehicles(rng, n_vehicles, mix)):
        lane = int(rng.integers(n_lanes))
        direction = -1 if lane < n_lanes / 2 else 1
        slack = lane_width - W
        x0 = lane * lane_width + slack / 2 + rng.uniform(-0.35, 0.35) * slack
        enter = next_free[lane]
        next_free[lane] = enter + (L / speeds[lane]) + min_gap + rng.exponential(mean_gap)
        colour = rng.uniform(40, 230, 3)
        vehicles.append(RoadVehicle(i + 1, cls, VEHICLE_CLASSES[cls]["heavy"], W, H, L, lane, direction,
                                    float(speeds[lane]), float(x0), float(enter), colour))
    # Ids in order of entry.
    vehicles.sort(key=lambda v: v.enter)
    for i, v in enumerate(vehicles):
        v.id = i + 1
    scene = RoadScene(setup, vehicles, _frames_to_clear(vehicles, y_range, fps), fps, n_lanes, lane_width, y_range,
                      seed, noise_std)
    scene._rays, scene._fov = _pixel_rays(setup)
    scene._background = _road_background(setup, scene._rays, n_lanes, lane_width, seed)
    return scene


def _frames_to_clear(vehicles: Sequence[RoadVehicle], y_range: Tuple[float, float], fps: float) -> int:
    """Frames until the last vehicle has left the simulated stretch."""
    stretch = y_range[1] - y_range[0]
    return int(math.ceil(max(v.enter + (stretch + v.L + 2.0) / v.speed for v in vehicles) * fps))


def _pixel_rays(setup: CameraSetup) -> Tuple[np.ndarray, Tuple[np.ndarray, np.ndarray]]:
    """H x W x 3 world directions of the rays through the pixel centres (R^T (x_n, y_n, 1)), and
    the bounding box (lo, hi) of the pixels' normalised coordinates (x_n, y_n), 2 % wider."""
    w, h = setup.image_width, setup.image_height
    xs, ys = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    n = _undistort_normalised(np.column_stack([xs.ravel(), ys.ravel()]), setup.K(), setup.dist)
    d = np.column_stack([n, np.ones(len(n))]) @ setup.rotation()
    # A zero component would make the slab test compute 0/0 for a box face through the centre;
    # 1e-12 changes no intersection by more than ~1e-10 m.
    d[d == 0.0] = 1e-12
    lo, hi = n.min(axis=0), n.max(axis=0)
    pad = 0.01 * (hi - lo)
    return d.reshape(h, w, 3), (lo - pad, hi + pad)


def _road_background(setup: CameraSetup, rays: np.ndarray, n_lanes: int, lane_width: float, seed: int) -> np.ndarray:
    """The static background: textured asphalt with lane markings, grass beyond the shoulders,
    sky above the horizon (float32 BGR)."""
    dz = rays[..., 2]
    ground = dz < -1e-9
    s = np.where(ground, setup.height / np.where(ground, -dz, 1.0), 0.0)
    X = setup.lateral + s * rays[..., 0]
    Y = setup.along + s * rays[..., 1]
    width = n_lanes * lane_width
    grain = 0.6 * _value_noise(X, Y, 0.15, seed) + 0.4 * _value_noise(X, Y, 1.7, seed + 1)
    asphalt = (95.0 + 14.0 * grain)[..., None] * np.array([1.0, 1.0, 1.02])
    grass = (np.array([60.0, 125.0, 85.0]) * (1.0 + 0.18 * _value_noise(X, Y, 0.4, seed + 2))[..., None])
    img = np.where(((X > -1.5) & (X < width + 1.5))[..., None], asphalt, grass)
    # Markings 0.15 m wide: solid road edges and centre line, dashed lines between lanes (3 m on, 9 m off).
    for k in range(n_lanes + 1):
        line = np.abs(X - k * lane_width) < 0.075
        solid = k in (0, n_lanes) or 2 * k == n_lanes
        if not solid:
            line &= np.mod(Y, 12.0) < 3.0
        img[line & ground] = 215.0
    sky = np.array([200.0, 170.0, 140.0]) + 30.0 * np.clip(-dz, -1, 0)[..., None]
    return np.where(ground[..., None], img, sky).astype(np.float32)


def read_ground_truth(folder: Union[str, os.PathLike]) -> Dict[str, np.ndarray]:
    """Reads what RoadScene.write wrote: 'vehicles' (structured array), 'boxes' (N, 8) and
    'silhouettes' (N, 5) float arrays."""
    folder = Path(folder)
    vehicles = np.genfromtxt(folder / "vehicles.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    boxes = np.loadtxt(folder / "boxes.csv", delimiter=",", skiprows=1, ndmin=2)
    sil = np.loadtxt(folder / "silhouettes.csv", delimiter=",", skiprows=1, ndmin=2)
    return {"vehicles": np.atleast_1d(vehicles), "boxes": boxes, "silhouettes": sil}

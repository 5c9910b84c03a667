"""Image-box tracking of detection files (MOTChallenge ``det.txt`` rows) with the GLMB tracker.

State [cx, vcx, cy, vcy, w, h]: the box centre moves with constant velocity (white-noise
acceleration, as rgbd-glmb-switching-observation eq. 7 in 2-D), the box size follows a random walk.
A detection (x, y, w, h) (top-left corner and size, pixels) is observed as its centre and size with
Gaussian noise. Tracks are born from the detections themselves (measurement-driven birth), since
people enter anywhere in an image.
"""

from __future__ import annotations

from typing import Sequence, Tuple

import numpy as np

from ._core import GlmbTracker, LinearGaussianMotion, LinearGaussianObservation

__all__ = ["box_models", "track_detections"]


def box_models(sigma_accel: float = 1.0, sigma_size: float = 1.0,
               detection_sd: Sequence[float] = (5.0, 5.0, 10.0, 10.0),
               ) -> Tuple[LinearGaussianMotion, LinearGaussianObservation]:
    """The motion and observation models of the box state [cx, vcx, cy, vcy, w, h] (one frame per
    step): constant-velocity centre with acceleration sd `sigma_accel` (px/frame^2), random-walk
    size with sd `sigma_size` (px/frame); detections (cx, cy, w, h) with sd `detection_sd` (px)."""
    cv = LinearGaussianMotion.constant_velocity(axes=2, period=1.0, sigma_v=sigma_accel)
    F, Q = np.eye(6), np.zeros((6, 6))
    F[:4, :4], Q[:4, :4] = cv.F, cv.Q
    Q[4, 4] = Q[5, 5] = float(sigma_size) ** 2
    H = np.zeros((4, 6))
    H[[0, 1, 2, 3], [0, 2, 4, 5]] = 1.0
    sd = np.asarray(detection_sd, dtype=float)
    if sd.shape != (4,) or not np.all(sd > 0):
        raise ValueError(f"detection_sd must be 4 positive numbers, got {detection_sd!r}")
    return LinearGaussianMotion(F, Q), LinearGaussianObservation(H, np.diag(sd ** 2))


def track_detections(det_rows, image_size: Tuple[int, int], *, min_confidence: float = -np.inf,
                     detection_probability: float = 0.9, survival_probability: float = 0.99,
                     clutter_rate: float = 1.0, sigma_accel: float = 1.0, sigma_size: float = 1.0,
                     detection_sd: Sequence[float] = (5.0, 5.0, 10.0, 10.0),
                     birth_sd: Sequence[float] = (10.0, 5.0, 10.0, 5.0, 10.0, 10.0),
                     birth_rate: float = 0.5, birth_max_existence: float = 0.3,
                     hypothesis_budget: int = 200) -> np.ndarray:
    """Tracks the boxes of MOTChallenge detection rows and returns MOTChallenge result rows.

    det_rows: (N, >= 6) array of ``frame, id, x, y, w, h[, conf, ...]`` (frames from 1; the id
    column is ignored), e.g. ``np.loadtxt("det.txt", delimiter=",")``. image_size: (width, height)
    in pixels; false detections are modelled as Poisson(`clutter_rate`) per frame, uniform over
    centres in the image and sizes up to the image size. Rows with conf < `min_confidence` are
    dropped. Births come only from detections (GlmbTracker's adaptive birth with covariance
    diag(birth_sd^2) over [cx, vcx, cy, vcy, w, h], `birth_rate` expected births per frame,
    existence capped at `birth_max_existence`). Motion and detection noise: see box_models.

    Returns a (K, 10) float64 array of ``frame, id, x, y, w, h, 1, -1, -1, -1`` for every frame
    from 1 to the last detection frame: the estimated boxes, ids 1, 2, ... in order of first
    appearance (one per GLMB track label).
    """
    rows = np.asarray(det_rows, dtype=float)
    if rows.ndim != 2 or (rows.size and rows.shape[1] < 6):
        raise ValueError(f"det_rows must be an (N, >= 6) array, got shape {rows.shape}")
    if rows.size and (np.isnan(rows[:, :6]).any() or (rows[:, 0] < 1).any()):
        raise ValueError("det_rows: frames must be >= 1 and the first six columns free of NaN")
    width, height = (float(v) for v in image_size)
    if not (width > 0 and height > 0):
        raise ValueError(f"image_size must be positive (width, height), got {image_size!r}")
    if rows.size and rows.shape[1] > 6:
        rows = rows[rows[:, 6] >= min_confidence]
    motion, observation = box_models(sigma_accel, sigma_size, detection_sd)
    tracker = GlmbTracker(
        motion, observation, [], survival_probability=survival_probability,
        detection_probability=detection_probability,
        clutter_intensity=max(clutter_rate, 1e-9) / (width * height) ** 2,
        hypothesis_budget=hypothesis_budget, max_hypotheses=hypothesis_budget,
        adaptive_birth_cov=np.diag(np.asarray(birth_sd, dtype=float) ** 2),
        adaptive_birth_rate=birth_rate, adaptive_birth_max_existence=birth_max_existence)
    frames = rows[:, 0].astype(np.int64) if rows.size else np.empty(0, np.int64)
    boxes = rows[:, 2:6] if rows.size else np.empty((0, 4))
    centres_sizes = np.column_stack([boxes[:, 0] + boxes[:, 2] / 2, boxes[:, 1] + boxes[:, 3] / 2,
                                     boxes[:, 2], boxes[:, 3]])
    ids = {}
    out = []
    for frame in range(1, int(frames.max(initial=0)) + 1):
        for e in tracker.step(centres_sizes[frames == frame]):
            track_id = ids.setdefault(e.label, len(ids) + 1)
            cx, cy, w, h = e.mean[[0, 2, 4, 5]]
            out.append([frame, track_id, cx - w / 2, cy - h / 2, w, h, 1, -1, -1, -1])
    return np.array(out, dtype=float).reshape(-1, 10)

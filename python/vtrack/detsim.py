"""A simulated box detector driven by real ground truth, for benchmarking detection-level trackers.

:func:`simulate_detections` turns MOTChallenge ground-truth rows (real trajectories, e.g.
PETS09-S2L1's) into the detections of an imperfect detector, frame by frame, with the textbook
model every multi-object filter assumes (Mahler's standard measurement model), plus the two ways
real detectors depart from it that trackers must survive:

- each true box is detected independently with probability ``detection_probability`` (p_D);
- on top of that, at the ``bursts`` level, each target has runs of 5-15 consecutive missed frames
  (occlusion, a pose the detector does not know): while a target is not in a run, a run starts at
  each of its frames with probability ``burst_rate``, its length uniform on ``burst_length``;
- a detected box's four corners are jittered independently by Gaussian noise with standard
  deviation ``corner_sd`` times the box's width (left, right) or height (top, bottom), so the
  error grows with the object's size as a detector's does;
- false detections are Poisson with mean ``clutter_rate`` per frame, person-sized (width and
  height drawn from the ground truth's own boxes, so the clutter matches the scene's people)
  and centred uniformly in the image;
- every detection has a score in (0, 1): Beta(``true_score``) for true detections and
  Beta(``false_score``) for false ones (defaults Beta(5, 2), mean 0.71, and Beta(2, 5), mean
  0.29: informative, overlapping, so a hard score cut loses true boxes or keeps false ones).

Ground-truth rows with confidence 0 (MOT15's "ignore" rows) are never detected, as the evaluation
ignores them. The four levels of issue 14 are in :data:`LEVELS`. Randomness comes only from
``numpy.random.default_rng(seed)``: same inputs and seed, same detections.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Optional, Tuple, Union

import numpy as np


@dataclass(frozen=True)
class DetectorLevel:
    """One simulated detector (see the module docstring for the model)."""

    detection_probability: float
    clutter_rate: float          # expected false boxes per frame (Poisson)
    corner_sd: float             # corner noise, fraction of the box's width / height
    burst_rate: float = 0.0      # per-frame probability that a burst of misses starts
    burst_length: Tuple[int, int] = (5, 15)   # inclusive range of a burst's length, frames
    true_score: Tuple[float, float] = (5.0, 2.0)    # Beta(a, b) of true detections' scores
    false_score: Tuple[float, float] = (2.0, 5.0)   # Beta(a, b) of false detections' scores

    def __post_init__(self) -> None:
        if not 0.0 <= self.detection_probability <= 1.0:
            raise ValueError(f"detection_probability must be in [0, 1], got "
                             f"{self.detection_probability}")
        if not (self.clutter_rate >= 0.0 and np.isfinite(self.clutter_rate)):
            raise ValueError(f"clutter_rate must be finite and >= 0, got {self.clutter_rate}")
        if not (self.corner_sd >= 0.0 and np.isfinite(self.corner_sd)):
            raise ValueError(f"corner_sd must be finite and >= 0, got {self.corner_sd}")
        if not 0.0 <= self.burst_rate <= 1.0:
            raise ValueError(f"burst_rate must be in [0, 1], got {self.burst_rate}")
        lo, hi = self.burst_length
        if not 1 <= lo <= hi:
            raise ValueError(f"burst_length must be 1 <= low <= high, got {self.burst_length}")
        for name in ("true_score", "false_score"):
            a, b = getattr(self, name)
            if not (a > 0 and b > 0):
                raise ValueError(f"{name} must be two positive Beta parameters, got {(a, b)}")


# Issue 14's four levels. Noise: "small, larger, larger still" as 3 %, 6 % and 10 % of the box
# per corner; the bursts level adds runs of misses (one starting every 1 / 0.03 = 33 frames of a
# target on average, so about a quarter of its frames fall in a run) to p_D 0.9, with one false
# box per frame and 4 % noise.
LEVELS: Dict[str, DetectorLevel] = {
    "easy": DetectorLevel(0.95, 0.5, 0.03),
    "medium": DetectorLevel(0.8, 3.0, 0.06),
    "hard": DetectorLevel(0.6, 8.0, 0.10),
    "bursts": DetectorLevel(0.9, 1.0, 0.04, burst_rate=0.03),
}


def _level(level: Union[str, DetectorLevel]) -> DetectorLevel:
    if isinstance(level, DetectorLevel):
        return level
    if isinstance(level, str) and level in LEVELS:
        return LEVELS[level]
    raise ValueError(f"level must be one of {sorted(LEVELS)} or a DetectorLevel, got {level!r}")


def _ground_truth(gt_rows) -> np.ndarray:
    gt = np.asarray(gt_rows, np.float64)
    if gt.size == 0:
        return np.empty((0, 10))
    if gt.ndim != 2 or gt.shape[1] < 7:
        raise ValueError(f"gt_rows must be a MOT table of at least 7 columns, got shape {gt.shape}")
    if not np.all(np.isfinite(gt[:, :7])):
        raise ValueError("gt_rows contain NaN or infinite values")
    gt = gt[gt[:, 6] != 0]
    return gt[np.lexsort((gt[:, 0], gt[:, 1]))]  # by id, then frame


def _detected(gt: np.ndarray, level: DetectorLevel, rng: np.random.Generator) -> np.ndarray:
    """Boolean mask over the (id, frame)-sorted GT rows: detected or not."""
    detected = rng.random(len(gt)) < level.detection_probability
    if level.burst_rate > 0.0:
        lo, hi = level.burst_length
        ids = gt[:, 1]
        remaining = 0
        for i in range(len(gt)):
            if i > 0 and ids[i] != ids[i - 1]:
                remaining = 0  # a new target: its own bursts
            if remaining == 0 and rng.random() < level.burst_rate:
                remaining = int(rng.integers(lo, hi + 1))
            if remaining > 0:
                detected[i] = False
                remaining -= 1
    return detected


def simulate_detections(gt_rows, level: Union[str, DetectorLevel], seed: int,
                        image_size: Tuple[float, float], *, last_frame: Optional[int] = None,
                        return_truth: bool = False):
    """Detections of the simulated detector `level` on ground truth `gt_rows`.

    Parameters
    ----------
    gt_rows : (N, >= 7) MOTChallenge rows (frame, id, x, y, w, h, conf, ...); conf-0 rows ignored.
    level : a name of :data:`LEVELS` ("easy", "medium", "hard", "bursts") or a DetectorLevel.
    seed : seed of the random generator.
    image_size : (width, height) of the image; clutter centres are uniform in it.
    last_frame : clutter is drawn on frames 1 .. last_frame (default: the GT's last frame).
    return_truth : also return, per detection, the GT id it comes from (-1 for clutter).

    Returns
    -------
    (M, 10) float64 MOT det rows ``frame, -1, x, y, w, h, score, -1, -1, -1`` sorted by frame
    (true and false detections shuffled within a frame), and with ``return_truth`` the (M,) int64
    GT ids.
    """
    lv = _level(level)
    width, height = (float(v) for v in image_size)
    if not (width > 0 and height > 0 and np.isfinite(width) and np.isfinite(height)):
        raise ValueError(f"image_size must be two positive numbers, got {image_size!r}")
    gt = _ground_truth(gt_rows)
    if last_frame is None:
        last_frame = int(gt[:, 0].max()) if len(gt) else 0
    if last_frame < 0:
        raise ValueError(f"last_frame must be >= 0, got {last_frame}")
    rng = np.random.default_rng(seed)

    true = gt[_detected(gt, lv, rng)]
    w, h = true[:, 4], true[:, 5]
    scale = np.stack([w, h, w, h], axis=1)
    corners = np.stack([true[:, 2], true[:, 3], true[:, 2] + w, true[:, 3] + h], axis=1)
    corners = corners + rng.normal(0.0, lv.corner_sd, corners.shape) * scale
    true_boxes = np.stack([corners[:, 0], corners[:, 1],
                           np.maximum(corners[:, 2] - corners[:, 0], 1.0),
                           np.maximum(corners[:, 3] - corners[:, 1], 1.0)], axis=1)
    true_scores = rng.beta(*lv.true_score, len(true))

    counts = rng.poisson(lv.clutter_rate, last_frame) if last_frame else np.zeros(0, np.int64)
    n_false = int(counts.sum())
    false_frames = np.repeat(np.arange(1, last_frame + 1), counts)
    if n_false and len(gt) == 0:
        raise ValueError("gt_rows has no box to take clutter sizes from")
    sizes = gt[rng.integers(0, len(gt), n_false), 4:6] if n_false else np.empty((0, 2))
    centres = rng.random((n_false, 2)) * [width, height]
    false_boxes = np.concatenate([centres - sizes / 2, sizes], axis=1)
    false_scores = rng.beta(*lv.false_score, n_false)

    frames = np.concatenate([true[:, 0], false_frames])
    boxes = np.concatenate([true_boxes, false_boxes])
    scores = np.concatenate([true_scores, false_scores])
    truth = np.concatenate([true[:, 1].astype(np.int64), np.full(n_false, -1, np.int64)])
    order = np.lexsort((rng.random(len(frames)), frames))
    rows = np.full((len(frames), 10), -1.0)
    rows[:, 0] = frames[order]
    rows[:, 2:6] = boxes[order]
    rows[:, 6] = scores[order]
    return (rows, truth[order]) if return_truth else rows

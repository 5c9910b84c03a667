"""A synthetic RGB-D people-tracking scene with exact ground truth (rgbd-glmb-switching-observation).

People walk in 3-D in front of a simulated Kinect (camera frame, metres: X right, Y down, D along
the optical axis; the camera 1.5 m above a flat floor, looking horizontally, as the paper's
sensor tower). Each frame (30 Hz) gives

* detections: noisy 3-D positions z = H x + w, w ~ N(0, Sigma) (eq. 2, H picks X, Y, D) of the
  people a detector found, plus Poisson clutter uniform over the viewing volume. Every person has
  *bursts* of missed detections (several frames to a second) besides the occasional isolated
  miss -- the situation the paper's switching model is for;
* a depth image rendered from the scene: the static background (a back wall and the floor), each
  person as a rectangle of their metric size at their depth (nearer people occlude farther ones),
  converted to 11-bit Kinect raw values with the inverse of eq. (3), noise and dropouts added on
  raw, rounded, converted back to metres with eq. (3), then background-subtracted: pixels within a
  tolerance of the known background depth (and pixels with no reading) become 0.

People are rendered as their projected rectangles, the shape eq. (4)'s T(x) assumes. (With
ellipses, 78 % of the rectangle, a footprint shrunk inside the silhouette -- the state pushed
farther away -- scores higher than the true one: the depth likelihood then biases D outwards and
sustains duplicate tracks behind a person; measured, not assumed.)

The person's state is eq. (7)'s [X, vX, Y, vY, D, vD] with (X, Y, D) the centre of their
bounding box; the DepthLikelihood of ``RgbdScene.depth_model()`` models them as rectangles.

The raw conversion uses the IR camera's native focal length (525 px at 640 x 480, the sensor's
disparity scale) whatever the rendered resolution; projection uses the rendered camera's fx.

>>> scene = make_rgbd_scene(seed=0, frames=60)
>>> scene.depth(0).shape
(240, 320)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

from ._core import (DepthLikelihood, GlmbTracker, LinearGaussianMotion, LinearGaussianObservation,
                    kinect_depth_to_raw, kinect_raw_to_depth)

PERIOD = 1.0 / 30.0          # Kinect frame rate (the paper's data set: 30 Hz)
CAMERA_HEIGHT = 1.5          # metres above the floor (the paper's sensor tower)
PERSON_SIZE = (0.5, 1.7)     # metric width, height of a person's bounding box
IR_FOCAL = 525.0             # IR camera fx at the sensor's native 640 x 480: eq. (3)'s F_x
WALL_DEPTH = 7.5             # the back wall of the room (m)
TURN = 1.5                   # deceleration of a person turning back at the edge of the view (m/s^2)
SIGMA_V = 1.5                # the trackers' eq. (7) process noise (m/s^2)


@dataclass
class RgbdScene:
    """Ground truth, detections and the depth renderer of one synthetic RGB-D sequence.

    truth_states[k]: (N_k, 6) states [X, vX, Y, vY, D, vD] at frame k; truth_ids[k]: their ids;
    detections[k]: (M_k, 3) noisy (X, Y, D) of detected people then clutter (a tracker must not
    rely on the order); missed[k]: ids whose detection was withheld at frame k (bursts and
    isolated misses); bursts: (id, first frame, last frame) of every burst.
    """

    truth_states: List[np.ndarray]
    truth_ids: List[np.ndarray]
    detections: List[np.ndarray]
    missed: List[np.ndarray]
    bursts: List[Tuple[int, int, int]]
    seed: int
    width: int = 320
    height: int = 240
    fx: float = 262.5
    detection_sigma: Tuple[float, float, float] = (0.05, 0.05, 0.1)
    detection_probability: float = 0.95
    clutter_rate: float = 2.0
    region: np.ndarray = field(default_factory=lambda: np.array([[-3.5, 3.5], [-0.5, 1.5],
                                                                 [1.0, 7.5]]))
    raw_noise: float = 1.0       # std. dev. of the raw-value noise (11-bit units)
    dropout: float = 0.02        # fraction of pixels with no reading
    _background: Optional[np.ndarray] = None

    @property
    def frames(self) -> int:
        return len(self.detections)

    @property
    def cx(self) -> float:
        return 0.5 * (self.width - 1)

    @property
    def cy(self) -> float:
        return 0.5 * (self.height - 1)

    @property
    def clutter_intensity(self) -> float:
        """Poisson clutter intensity per cubic metre (rate / viewing-volume box)."""
        return self.clutter_rate / float(np.prod(self.region[:, 1] - self.region[:, 0]))

    def truth_positions(self, k: int) -> np.ndarray:
        """(N, 3) true (X, Y, D) at frame k."""
        return self.truth_states[k][:, [0, 2, 4]]

    def background(self) -> np.ndarray:
        """Metric depth of the empty room (H x W float32): the floor below the horizon, the back
        wall elsewhere."""
        if self._background is None:
            v = np.arange(self.height, dtype=np.float64)[:, None] - self.cy
            with np.errstate(divide="ignore"):
                floor = np.where(v > 0, self.fx * CAMERA_HEIGHT / np.maximum(v, 1e-9), np.inf)
            bg = np.minimum(floor, WALL_DEPTH) * np.ones((1, self.width))
            self._background = bg.astype(np.float32)
        return self._background

    def render_metric(self, k: int) -> np.ndarray:
        """The noise-free metric depth image of frame k (background and people, occlusion)."""
        depth = self.background().copy()
        states = self.truth_states[k]
        vv, uu = np.mgrid[0:self.height, 0:self.width]
        for s in states[np.argsort(-states[:, 4])]:  # far to near: nearer people overwrite
            X, Y, D = s[0], s[2], s[4]
            if D <= 0.3:
                continue
            u, v = self.cx + self.fx * X / D, self.cy + self.fx * Y / D
            a, b = 0.5 * self.fx * PERSON_SIZE[0] / D, 0.5 * self.fx * PERSON_SIZE[1] / D
            inside = (np.abs(uu - u) <= a) & (np.abs(vv - v) <= b)
            depth[inside & (D < depth)] = D
        return depth

    def depth(self, k: int, background_tolerance: float = 0.15) -> np.ndarray:
        """The background-subtracted metric depth image of frame k (H x W float32, 0 = background
        or no reading), through the Kinect's raw coding: eq. (3)'s inverse, raw noise and
        dropouts, 11-bit rounding, eq. (3). Deterministic in (seed, k)."""
        rng = np.random.default_rng([self.seed, 7919, k])
        raw = kinect_depth_to_raw(self.render_metric(k).astype(np.float64), IR_FOCAL)
        raw = np.rint(raw + rng.normal(0.0, self.raw_noise, raw.shape))
        raw[rng.random(raw.shape) < self.dropout] = 2047.0
        metric = kinect_raw_to_depth(np.clip(raw, 0.0, 2047.0), IR_FOCAL)
        bg = self.background().astype(np.float64)
        # The tolerance grows with depth as the raw quantisation does (dT/dw = T^2 / (8 B F_x)).
        tol = background_tolerance + 3.0 * bg ** 2 / (8 * 0.075 * IR_FOCAL) * max(self.raw_noise, 0.5)
        metric[np.abs(metric - bg) <= tol] = 0.0
        return metric.astype(np.float32)

    def depth_model(self, **params) -> DepthLikelihood:
        """The DepthLikelihood of this scene's camera; keywords override its parameters."""
        return DepthLikelihood(self.width, self.height, self.fx, **{
            "person_width": PERSON_SIZE[0], "person_height": PERSON_SIZE[1], **params})

    def tracker(self, density: str = "particle", switching: bool = True, particles: int = 300,
                seed: int = 0, depth_params: Optional[Dict] = None, **params) -> GlmbTracker:
        """A GlmbTracker with this scene's model: eq. (7) constant velocity (sigma_v = 1.5 m/s^2),
        eq. (2) detections with the scene's Sigma, its clutter intensity and p_D, adaptive birth
        from detections. density "particle" (switching: with the depth model; step with depth=)
        or "gaussian" (Kalman, detection-only). Keywords override GlmbTracker parameters.

        One label per person is reported (label_duplicate_gate 11.34, the chi-square 0.99
        quantile of 3-D detections): through a burst of missed detections eq. (4)'s separable
        depth likelihood lets a second track live on a person's pixels beside the first, and the
        report then held both labels (benchmarks/rgbd_switching.py: seeds 15-19, 89 label
        switches, 55 with the gate; every seed set measured better)."""
        kwargs = dict(detection_probability=self.detection_probability,
                      clutter_intensity=self.clutter_intensity, survival_probability=0.999,
                      hypothesis_budget=200, max_hypotheses=200, gate_threshold=16.27,
                      adaptive_birth_cov=np.diag([0.1, 0.5, 0.1, 0.1, 0.2, 0.5]) ** 2,
                      adaptive_birth_rate=0.01, adaptive_birth_max_existence=0.01,
                      label_duplicate_gate=11.34)
        if density == "particle":
            kwargs.update(densities="particles", n_particles=particles, seed=seed)
            if switching:
                kwargs["depth_model"] = self.depth_model(**(depth_params or {}))
        elif density != "gaussian" or switching:
            raise ValueError("density must be 'particle' or 'gaussian' (detection-only), got "
                             f"{density!r} with switching={switching}")
        kwargs.update(params)
        motion = LinearGaussianMotion.constant_velocity(axes=3, period=PERIOD, sigma_v=SIGMA_V)
        observation = LinearGaussianObservation.position(
            axes=3, R=np.diag(np.square(self.detection_sigma)))
        return GlmbTracker(motion, observation, [], **kwargs)


def positions(tracks) -> List[Tuple[int, np.ndarray]]:
    """[(id, (X, Y, D)), ...] of a GlmbTracker step's Tracks (state [X, vX, Y, vY, D, vD]): the
    per-frame estimates identity_events, burst_outcomes and clear_mot take."""
    if len(tracks) == 0:
        return []
    return [(int(i), s[[0, 2, 4]].copy()) for i, s in zip(tracks.ids, tracks.states)]


def make_rgbd_scene(seed: int = 0, frames: int = 300, people: int = 4,
                    burst_rate: float = 0.5, burst_frames: Tuple[int, int] = (8, 30),
                    **scene_params) -> RgbdScene:
    """People walking across the room (1.5-6 m from the camera), seeded.

    Each person walks at 0.4-1.2 m/s with a small random acceleration (eq. 7 with
    sigma_v = 0.3 m/s^2 in X and D; Y, the box centre's height, stays 0.85 m above the floor),
    enters at a staggered frame and is kept inside the field of view (turning back smoothly at
    TURN m/s^2 near its edges). Missed-detection bursts:
    on average burst_rate per person per second, each lasting a uniform number of frames in
    burst_frames (8-30 frames = 0.27-1 s), never in a person's first 15 frames; outside bursts a
    person is detected with probability detection_probability.
    """
    rng = np.random.default_rng(seed)
    scene = RgbdScene([], [], [], [], [], seed, **scene_params)
    half_fov = 0.5 * scene.width / scene.fx * 0.85  # stay inside the image, with a margin
    y_centre = CAMERA_HEIGHT - 0.5 * PERSON_SIZE[1]
    starts = np.sort(rng.integers(0, max(1, frames // 3), size=people))
    starts[0] = 0
    lives = []
    for p in range(people):
        D = rng.uniform(1.8, 5.5)
        X = rng.uniform(-0.8, 0.8) * half_fov * D
        heading = rng.uniform(0, 2 * np.pi)
        speed = rng.uniform(0.4, 1.2)
        lives.append(np.array([X, speed * np.cos(heading), y_centre, 0.0, D,
                               speed * np.sin(heading)]))
    # Bursts of missed detections per person.
    burst_mask = np.zeros((people, frames), bool)
    for p in range(people):
        k = starts[p] + 15
        while True:
            k += int(rng.exponential(1.0 / (burst_rate * PERIOD)))
            if k >= frames:
                break
            length = int(rng.integers(burst_frames[0], burst_frames[1] + 1))
            burst_mask[p, k:k + length] = True
            scene.bursts.append((p, k, min(frames, k + length) - 1))
            k += length
    F = LinearGaussianMotion.constant_velocity(axes=3, period=PERIOD, sigma_v=0.3).F
    sigma = np.asarray(scene.detection_sigma)
    lo, hi = scene.region[:, 0], scene.region[:, 1]
    for k in range(frames):
        states, ids, z, missed = [], [], [], []
        for p in range(people):
            if k < starts[p]:
                continue
            if k > starts[p]:
                x = F @ lives[p]
                acc = rng.normal(0.0, 0.3, 2)
                # Walls: turn back smoothly (TURN m/s^2) when heading out of the field of view
                # or the 1.5-6 m band, as a person would -- no instantaneous reversals.
                x_edge = half_fov * x[4] - 0.4
                if abs(x[0]) > x_edge and x[0] * x[1] > 0:
                    acc[0] -= np.sign(x[1]) * TURN
                if (x[4] < 1.8 and x[5] < 0) or (x[4] > 5.7 and x[5] > 0):
                    acc[1] -= np.sign(x[5]) * TURN
                x[[0, 4]] += 0.5 * PERIOD ** 2 * acc
                x[[1, 5]] += PERIOD * acc
                lives[p] = x
            states.append(lives[p].copy())
            ids.append(p)
            if burst_mask[p, k] or rng.random() >= scene.detection_probability:
                missed.append(p)
            else:
                z.append(lives[p][[0, 2, 4]] + rng.normal(size=3) * sigma)
        n_clutter = rng.poisson(scene.clutter_rate)
        clutter = lo + (hi - lo) * rng.random((n_clutter, 3))
        scene.truth_states.append(np.array(states).reshape(-1, 6))
        scene.truth_ids.append(np.array(ids, dtype=np.int64))
        scene.detections.append(np.vstack([np.array(z).reshape(-1, 3), clutter]))
        scene.missed.append(np.array(missed, dtype=np.int64))
    return scene


@dataclass
class IdentityEvents:
    """Per-sequence identity statistics of labelled estimates against the truth ids.

    matched_frames: truth-frames with an estimate assigned; truth_frames: all truth-frames;
    label_switches: times a truth id's assigned label differs from the label it was last
    assigned (CLEAR-MOT's ID switch); fragmentations: times a truth id's coverage resumes after
    an interruption (it was assigned, then not, then assigned again: CLEAR-MOT's Frag);
    burst_coverage: fraction of a person's missed-detection-burst frames in which an estimate is
    assigned to them (1.0 when there are no bursts).
    """

    matched_frames: int
    truth_frames: int
    label_switches: int
    fragmentations: int
    burst_coverage: float


def match_frame(truth: np.ndarray, estimates: np.ndarray, gate: float) -> List[Tuple[int, int]]:
    """Optimal one-to-one assignment (minimum total distance, as many pairs as possible) between
    the rows of truth (N, d) and estimates (M, d), keeping only pairs closer than gate."""
    from ._core import linear_assignment
    if len(truth) == 0 or len(estimates) == 0:
        return []
    dist = np.linalg.norm(truth[:, None, :] - estimates[None, :, :], axis=2)
    # Pairs beyond the gate cost more than any set of gated pairs, so the assignment first
    # maximises the number of gated pairs, then minimises their total distance.
    cost = np.where(dist <= gate, dist, gate * (len(truth) + len(estimates) + 1))
    transpose = len(truth) > len(estimates)
    rows, cols = linear_assignment(cost.T if transpose else cost)
    pairs = [(int(c), int(r)) if transpose else (int(r), int(c)) for r, c in zip(rows, cols)]
    return [(i, j) for i, j in pairs if dist[i, j] <= gate]


def identity_events(scene: RgbdScene, estimates: List[List[Tuple[Tuple[int, int], np.ndarray]]],
                    gate: float = 0.5) -> IdentityEvents:
    """Label switches and fragmentations of per-frame estimates [(label, (X, Y, D)), ...] against
    the scene's truth, with the per-frame optimal assignment of match_frame within `gate`
    metres."""
    last_label: Dict[int, Tuple[int, int]] = {}
    covered: Dict[int, bool] = {}
    switches = fragments = matched = total = 0
    burst_hits = burst_total = 0
    in_burst = _burst_lookup(scene)
    for k, assigned in enumerate(_assignments(scene, estimates, gate)):
        for tid in scene.truth_ids[k].tolist():
            total += 1
            label = assigned.get(tid)
            if (tid, k) in in_burst:
                burst_total += 1
                burst_hits += label is not None
            if label is None:
                if covered.get(tid):
                    covered[tid] = False
                continue
            matched += 1
            if tid in last_label and last_label[tid] != label:
                switches += 1
            if covered.get(tid) is False:  # was covered before, then lost: coverage resumes
                fragments += 1
            last_label[tid] = label
            covered[tid] = True
    return IdentityEvents(matched, total, switches, fragments,
                          burst_hits / burst_total if burst_total else 1.0)


def _burst_lookup(scene: RgbdScene) -> set:
    return {(pid, k) for pid, first, last in scene.bursts for k in range(first, last + 1)}


@dataclass
class BurstOutcomes:
    """What became of each person's label across each of their missed-detection bursts (the
    paper's claim: a detection-only tracker "treats the same object as a new track after few time
    steps" of missed detections).

    For a burst (id, first, last): the label before is the one assigned to the person (within the
    gate, match_frame) at the last matched frame in the `window` frames before `first`; the label
    after, the first one assigned in the `window` frames after `last`. kept: the same label;
    relabelled: another label (the person was re-born, or taken over by another track); lost: no
    estimate near the person in that window; untracked: no label before the burst (not scored).
    """

    kept: int
    relabelled: int
    lost: int
    untracked: int


def _assignments(scene: RgbdScene, estimates, gate: float) -> List[Dict[int, object]]:
    """Per frame, {truth id: label} of the optimal assignment within `gate` (match_frame)."""
    out = []
    for k, frame in enumerate(estimates):
        ids = scene.truth_ids[k]
        est = np.array([e[1] for e in frame]).reshape(-1, 3)
        out.append({int(ids[i]): frame[j][0]
                    for i, j in match_frame(scene.truth_positions(k), est, gate)})
    return out


def burst_outcomes(scene: RgbdScene, estimates, gate: float = 0.5,
                   window: int = 30) -> BurstOutcomes:
    """BurstOutcomes of per-frame estimates [(label, (X, Y, D)), ...] (window: 1 s at 30 Hz)."""
    assigned = _assignments(scene, estimates, gate)
    counts = dict(kept=0, relabelled=0, lost=0, untracked=0)

    def first_label(frames_range, pid):
        return next((assigned[k][pid] for k in frames_range if pid in assigned[k]), None)

    for pid, first, last in scene.bursts:
        before = first_label(range(first - 1, max(-1, first - 1 - window), -1), pid)
        after = first_label(range(last + 1, min(len(assigned), last + 1 + window)), pid)
        if before is None:
            counts["untracked"] += 1
        elif last + 1 >= len(assigned):
            continue  # the burst runs to the end of the sequence: no outcome to score
        elif after is None:
            counts["lost"] += 1
        else:
            counts["kept" if after == before else "relabelled"] += 1
    return BurstOutcomes(**counts)


def clear_mot(scene: RgbdScene, estimates, gate: float = 0.5) -> Dict[str, float]:
    """TrackEval's CLEAR-MOT (MOTA, IDSW, Frag, ...), IDF1 and HOTA of per-frame estimates
    [(label, (X, Y, D)), ...] on 3-D positions: the similarity of a truth-estimate pair is
    1 - distance / (2 gate), clipped at 0, so TrackEval's match threshold 0.5 is a distance of
    `gate` metres (HOTA's thresholds 0.05..0.95 span distances 1.9 gate .. 0.1 gate). Unlike
    identity_events, TrackEval keeps last frame's matches where they remain valid before
    assigning the rest (CLEAR-MOT), so crossing people are not re-paired frame by frame; and it
    skips a frame with no estimates at all without ending the matches (no Frag for that gap)."""
    from .evaluate import evaluate_sequence
    labels = sorted({lab for frame in estimates for lab, _ in frame})
    label_index = {lab: i for i, lab in enumerate(labels)}
    truth_index = {t: i for i, t in enumerate(sorted({int(t) for ids in scene.truth_ids
                                                      for t in ids}))}
    data = {"num_timesteps": len(estimates), "num_gt_ids": len(truth_index),
            "num_tracker_ids": len(labels), "num_gt_dets": 0, "num_tracker_dets": 0,
            "gt_ids": [], "tracker_ids": [], "similarity_scores": []}
    for k, frame in enumerate(estimates):
        truth = scene.truth_positions(k)
        est = np.array([e[1] for e in frame]).reshape(-1, 3)
        data["gt_ids"].append(np.array([truth_index[int(t)] for t in scene.truth_ids[k]], int))
        data["tracker_ids"].append(np.array([label_index[lab] for lab, _ in frame], int))
        dist = np.linalg.norm(truth[:, None, :] - est[None, :, :], axis=2)
        data["similarity_scores"].append(np.clip(1.0 - dist / (2.0 * gate), 0.0, None))
        data["num_gt_dets"] += len(truth)
        data["num_tracker_dets"] += len(est)
    return evaluate_sequence(data)

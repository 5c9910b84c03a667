"""Synthetic multi-target scenarios with exact ground truth, for testing and benchmarking trackers.

The standard linear-Gaussian GLMB scenario is B.-N. Vo's demo (used in Vo, Vo & Hoang, "An
Efficient Implementation of the Generalized Labeled Multi-Bernoulli Filter", IEEE TSP 2017): twelve
targets with noiseless constant-velocity truth over 100 scans in [-1000, 1000]^2 m, position
detections with p_D = 0.98 and R = 100 I, Poisson clutter uniform on the square. The constants
below are those of its ``model.json`` (shipped with the project's shared data as
``glmb-standard/``), which also holds ten fixed measurement draws; ``load_standard_glmb_draw``
reads one of them.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import List, Sequence, Tuple, Union

import numpy as np

from ._core import GlmbTracker, LinearGaussianMotion, LinearGaussianObservation

__all__ = [
    "GlmbScenario",
    "STANDARD_BIRTHS",
    "STANDARD_REGION",
    "STANDARD_TARGETS",
    "load_standard_glmb_draw",
    "standard_glmb_scenario",
]

#: (track_id, start state [x, vx, y, vy], birth scan, death scan) of the twelve targets. A target
#: exists at scans birth .. min(death, K) and its state at its birth scan is F @ start (Vo's demo).
STANDARD_TARGETS: Tuple[Tuple[int, Tuple[float, float, float, float], int, int], ...] = (
    (1, (0, 0, 0, -10), 1, 70),
    (2, (400, -10, -600, 5), 1, 101),
    (3, (-800, 20, -200, -5), 1, 70),
    (4, (400, -7, -600, -4), 20, 101),
    (5, (400, -2.5, -600, 10), 20, 101),
    (6, (0, 7.5, 0, -5), 20, 101),
    (7, (-800, 12, -200, 7), 40, 101),
    (8, (-200, 15, 800, -10), 40, 101),
    (9, (-800, 3, -200, 15), 60, 101),
    (10, (-200, -3, 800, -15), 60, 101),
    (11, (0, -20, 0, -15), 80, 101),
    (12, (-200, 15, 800, -5), 80, 101),
)

#: The LMB birth model: (existence, mean, cov) per component, for GlmbTracker(births=...).
STANDARD_BIRTHS: List[Tuple[float, np.ndarray, np.ndarray]] = [
    (0.03, np.array(mean, dtype=float), np.eye(4) * 100.0)
    for mean in ((0.1, 0.0, 0.1, 0.0), (400.0, 0.0, -600.0, 0.0), (-800.0, 0.0, -200.0, 0.0),
                 (-200.0, 0.0, 800.0, 0.0))
]

#: Surveillance region [[x_min, x_max], [y_min, y_max]] (m); clutter is uniform on it.
STANDARD_REGION = np.array([[-1000.0, 1000.0], [-1000.0, 1000.0]])

_SCANS = 100
_PERIOD = 1.0
_SIGMA_V = 5.0
_R = np.eye(2) * 100.0


@dataclass
class GlmbScenario:
    """Ground truth and measurements of a 2-D linear-Gaussian scenario, one entry per scan.

    truth_states[k]: (N_k, 4) true states [x, vx, y, vy] at scan k + 1; truth_ids[k]: their track
    ids; measurements[k]: (M_k, 2) detections and clutter at scan k + 1 (detections first, in
    target order, then clutter -- a tracker must not rely on it); clutter_rate: mean clutter count
    per scan; detection_probability: p_D used to draw the detections.
    """

    truth_states: List[np.ndarray]
    truth_ids: List[np.ndarray]
    measurements: List[np.ndarray]
    clutter_rate: float = 30.0
    detection_probability: float = 0.98
    region: np.ndarray = field(default_factory=lambda: STANDARD_REGION.copy())

    @property
    def scans(self) -> int:
        """Number of scans."""
        return len(self.measurements)

    def truth_positions(self, k: int) -> np.ndarray:
        """(N, 2) true [x, y] at scan index k (0-based), as the OSPA of the literature uses."""
        return self.truth_states[k][:, [0, 2]]

    @property
    def clutter_intensity(self) -> float:
        """Poisson clutter intensity per unit area: the rate over the region's area."""
        return self.clutter_rate / float(np.prod(self.region[:, 1] - self.region[:, 0]))

    def tracker(self, **params) -> GlmbTracker:
        """A GlmbTracker with this scenario's model (motion, observation, births, p_D, clutter
        intensity); keyword arguments override or add GlmbTracker parameters."""
        kwargs = dict(detection_probability=self.detection_probability,
                      clutter_intensity=self.clutter_intensity)
        kwargs.update(params)
        return GlmbTracker(LinearGaussianMotion.constant_velocity(2, _PERIOD, _SIGMA_V),
                           LinearGaussianObservation.position(2, _R), STANDARD_BIRTHS, **kwargs)


def _standard_truth(scans: int = _SCANS) -> Tuple[List[np.ndarray], List[np.ndarray]]:
    F = LinearGaussianMotion.constant_velocity(2, _PERIOD, _SIGMA_V).F
    states: List[List[np.ndarray]] = [[] for _ in range(scans)]
    ids: List[List[int]] = [[] for _ in range(scans)]
    for track_id, start, birth, death in STANDARD_TARGETS:
        x = np.array(start, dtype=float)
        for k in range(birth, min(death, scans) + 1):
            x = F @ x  # noiseless constant velocity, as Vo's demo
            states[k - 1].append(x)
            ids[k - 1].append(track_id)
    return ([np.array(s).reshape(-1, 4) for s in states],
            [np.array(i, dtype=np.int64) for i in ids])


def standard_glmb_scenario(seed: int, clutter_rate: float = 30.0,
                           detection_probability: float = 0.98,
                           scans: int = _SCANS) -> GlmbScenario:
    """Draws the measurements of the standard GLMB scenario with NumPy's generator seeded by `seed`.

    Each existing target is detected with probability `detection_probability` at [x, y] plus
    N(0, 100 I) noise; a Poisson(`clutter_rate`) number of clutter points follows, uniform on
    [-1000, 1000]^2. The truth is the fixed noiseless truth of the scenario (equal to the shared
    data's truth.csv). The draws differ from the shared data's ten fixed draws (another generator).
    """
    if clutter_rate < 0 or not np.isfinite(clutter_rate):
        raise ValueError(f"clutter_rate must be >= 0 and finite, got {clutter_rate}")
    if not 0.0 <= detection_probability <= 1.0:
        raise ValueError(f"detection_probability must lie in [0, 1], got {detection_probability}")
    if scans < 1:
        raise ValueError(f"scans must be >= 1, got {scans}")
    rng = np.random.default_rng(seed)
    states, ids = _standard_truth(scans)
    noise_sd = np.sqrt(np.diag(_R))
    lo, hi = STANDARD_REGION[:, 0], STANDARD_REGION[:, 1]
    measurements = []
    for x in states:
        detected = x[rng.random(len(x)) < detection_probability]
        z = detected[:, [0, 2]] + rng.normal(size=(len(detected), 2)) * noise_sd
        clutter = lo + (hi - lo) * rng.random((rng.poisson(clutter_rate), 2))
        measurements.append(np.vstack([z, clutter]))
    return GlmbScenario(states, ids, measurements, clutter_rate, detection_probability)


def load_standard_glmb_draw(seed_dir: Union[str, Path]) -> GlmbScenario:
    """Reads one fixed draw of the shared data (``glmb-standard/seedN``): its measurements.csv
    (``k,x,y``) and the scenario's truth.csv (``k,track_id,x,vx,y,vy``) in the folder above it."""
    seed_dir = Path(seed_dir)
    truth_path = seed_dir.parent / "truth.csv"
    rows = _read_csv(truth_path)
    scans = int(max(r[0] for r in rows))
    states: List[List[Sequence[float]]] = [[] for _ in range(scans)]
    ids: List[List[int]] = [[] for _ in range(scans)]
    for k, track_id, *x in rows:
        states[int(k) - 1].append(x)
        ids[int(k) - 1].append(int(track_id))
    points: List[List[Sequence[float]]] = [[] for _ in range(scans)]
    for k, *z in _read_csv(seed_dir / "measurements.csv"):
        if not 1 <= k <= scans:
            raise ValueError(f"{seed_dir / 'measurements.csv'}: scan {int(k)} outside 1..{scans}")
        points[int(k) - 1].append(z)
    return GlmbScenario([np.array(s, dtype=float).reshape(-1, 4) for s in states],
                        [np.array(i, dtype=np.int64) for i in ids],
                        [np.array(p, dtype=float).reshape(-1, 2) for p in points])


def _read_csv(path: Path) -> List[List[float]]:
    if not path.exists():
        raise FileNotFoundError(f"no such file: {path}")
    with open(path, newline="") as f:
        reader = csv.reader(f)
        next(reader)  # header
        return [[float(v) for v in row] for row in reader if row]

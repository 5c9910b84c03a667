"""Motion and observation models (the C++ ``models`` layer): linear-Gaussian motion (e.g. the
constant-velocity model of the RGB-D GLMB paper, eq. 7) and observation (eq. 2), the depth-intensity
likelihood of the RGB-D switching observation model (eq. 4, with the Kinect raw-to-metric
conversion of eq. 3), the ``ForegroundSizeEstimator`` that learns how tall a scene's people are
from its foreground (the multi-Bernoulli tracker's size prior), and the particle filters' models (``vtrack.smc``): ``LinearTransition`` and
its forms ``RandomWalk`` (mb-tbd eq. 22), ``ConstantVelocity`` (discrete or continuous
white-noise acceleration) and ``SecondOrderAutoRegressive`` (part-based eq. 13), and the
``RangeBearingObservation``.
"""

from ._core import (
    ConstantVelocity,
    DepthLikelihood,
    ForegroundSizeEstimator,
    LinearGaussianMotion,
    LinearGaussianObservation,
    LinearTransition,
    RandomWalk,
    RangeBearingObservation,
    SecondOrderAutoRegressive,
    kinect_depth_to_raw,
    kinect_raw_to_depth,
)

__all__ = [
    "ConstantVelocity",
    "DepthLikelihood",
    "ForegroundSizeEstimator",
    "LinearGaussianMotion",
    "LinearGaussianObservation",
    "LinearTransition",
    "RandomWalk",
    "RangeBearingObservation",
    "SecondOrderAutoRegressive",
    "kinect_depth_to_raw",
    "kinect_raw_to_depth",
]

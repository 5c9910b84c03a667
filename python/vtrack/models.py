"""Motion and observation models (the C++ ``models`` layer): linear-Gaussian motion (e.g. the
constant-velocity model of the RGB-D GLMB paper, eq. 7) and observation (eq. 2), and the
depth-intensity likelihood of the RGB-D switching observation model (eq. 4, with the Kinect
raw-to-metric conversion of eq. 3).
"""

from ._core import (
    DepthLikelihood,
    LinearGaussianMotion,
    LinearGaussianObservation,
    kinect_depth_to_raw,
    kinect_raw_to_depth,
)

__all__ = [
    "DepthLikelihood",
    "LinearGaussianMotion",
    "LinearGaussianObservation",
    "kinect_depth_to_raw",
    "kinect_raw_to_depth",
]

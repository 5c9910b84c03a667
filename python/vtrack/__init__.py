"""vtrack: Bayesian visual multi-object tracking.

The filters of four papers -- KDE background subtraction with a multi-Bernoulli
track-before-detect tracker, SIR/MCMC particle filters, a GLMB tracker with Murty's ranked
assignments, and colour/part-based particle filters -- in C++ with this Python API.

This release holds the SMC core the trackers are built from and the KDE background model
(``KdeBackground``, paper eqs. 6-10) that turns video frames into the grey image the
track-before-detect tracker consumes:

>>> import numpy as np, vtrack
>>> rng = vtrack.Rng(seed=1)
>>> w, log_z = vtrack.normalize_log_weights(np.log([0.1, 0.2, 0.7]))
>>> vtrack.effective_sample_size(w)  # 1 / sum(w**2)
1.8518518518518516
>>> vtrack.resample(w, rng, method="systematic")
array([1, 2, 2])

the GLMB multi-object tracker ``GlmbTracker`` (Gaussian delta-GLMB with Murty's ranked
assignments) with its linear-Gaussian models and the synthetic scenarios of ``vtrack.scenarios``,
and the data-association and evaluation tools of the trackers: ``linear_assignment``, Murty's
k-best assignments ``murty``, and the OSPA, OSPA(2) and GOSPA metrics.

NumPy arrays go in and out without copies where the layout allows; wrong dtypes raise
``TypeError``, wrong shapes or values ``ValueError`` (C++ errors arrive as
``vtrack.InvalidArgument``, a ``ValueError``, and ``vtrack.IoError``, an ``OSError``).
"""

from ._core import (
    Gaussian,
    GlmbEstimate,
    GlmbTracker,
    GospaResult,
    IntegralImage,
    InvalidArgument,
    IoError,
    LinearGaussianMotion,
    LinearGaussianObservation,
    OspaResult,
    KdeBackground,
    Rng,
    VideoInfo,
    __version__,
    bgr_to_rgi,
    close_square,
    effective_sample_size,
    gospa,
    linear_assignment,
    foreground_mask,
    log_sum_exp,
    murty,
    normalize_log_weights,
    ospa,
    ospa2,
    probe_video,
    resample,
)

from . import scenarios  # noqa: E402  (needs the compiled module above)
from .boxes import track_detections  # noqa: E402

RESAMPLING_METHODS = ("multinomial", "stratified", "systematic", "residual")

__all__ = [
    "Gaussian",
    "GlmbEstimate",
    "GlmbTracker",
    "GospaResult",
    "IntegralImage",
    "InvalidArgument",
    "IoError",
    "LinearGaussianMotion",
    "LinearGaussianObservation",
    "OspaResult",
    "KdeBackground",
    "RESAMPLING_METHODS",
    "Rng",
    "VideoInfo",
    "__version__",
    "bgr_to_rgi",
    "close_square",
    "effective_sample_size",
    "gospa",
    "linear_assignment",
    "foreground_mask",
    "log_sum_exp",
    "murty",
    "normalize_log_weights",
    "ospa",
    "ospa2",
    "probe_video",
    "resample",
    "scenarios",
    "track_detections",
]

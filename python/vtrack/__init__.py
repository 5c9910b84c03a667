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

NumPy arrays go in and out without copies where the layout allows; wrong dtypes raise
``TypeError``, wrong shapes or values ``ValueError`` (C++ errors arrive as
``vtrack.InvalidArgument``, a ``ValueError``, and ``vtrack.IoError``, an ``OSError``).
"""

from ._core import (
    Gaussian,
    IntegralImage,
    InvalidArgument,
    IoError,
    KdeBackground,
    Rng,
    VideoInfo,
    __version__,
    bgr_to_rgi,
    close_square,
    effective_sample_size,
    foreground_mask,
    log_sum_exp,
    normalize_log_weights,
    probe_video,
    resample,
)

RESAMPLING_METHODS = ("multinomial", "stratified", "systematic", "residual")

__all__ = [
    "Gaussian",
    "IntegralImage",
    "InvalidArgument",
    "IoError",
    "KdeBackground",
    "RESAMPLING_METHODS",
    "Rng",
    "VideoInfo",
    "__version__",
    "bgr_to_rgi",
    "close_square",
    "effective_sample_size",
    "foreground_mask",
    "log_sum_exp",
    "normalize_log_weights",
    "probe_video",
    "resample",
]

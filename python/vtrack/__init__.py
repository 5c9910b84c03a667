"""vtrack: Bayesian visual multi-object tracking.

The filters of four papers -- KDE background subtraction with a multi-Bernoulli
track-before-detect tracker, SIR/MCMC particle filters, a GLMB tracker with Murty's ranked
assignments, and colour/part-based particle filters -- in C++ with this Python API.

The multi-Bernoulli track-before-detect tracker consumes background-subtracted images
(H x W float32, near 1 = background): ``vtrack.MultiBernoulliTracker((width, height), seed=1)``
and ``.step(y)`` per frame; ``vtrack.mot`` writes MOTChallenge files, ``python -m
vtrack.evaluate`` scores them, ``vtrack.synthetic`` makes scenes with exact ground truth.

The SMC core the trackers are built from:

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
    BernoulliComponent,
    Gaussian,
    IntegralImage,
    InvalidArgument,
    IoError,
    MultiBernoulliTracker,
    Rng,
    Track,
    VideoInfo,
    __version__,
    bgr_to_rgi,
    effective_sample_size,
    log_sum_exp,
    normalize_log_weights,
    probe_video,
    resample,
)

RESAMPLING_METHODS = ("multinomial", "stratified", "systematic", "residual")

from . import mot, synthetic

__all__ = [
    "BernoulliComponent",
    "Gaussian",
    "IntegralImage",
    "InvalidArgument",
    "IoError",
    "MultiBernoulliTracker",
    "RESAMPLING_METHODS",
    "Rng",
    "Track",
    "VideoInfo",
    "__version__",
    "bgr_to_rgi",
    "effective_sample_size",
    "log_sum_exp",
    "mot",
    "normalize_log_weights",
    "probe_video",
    "resample",
    "synthetic",
]

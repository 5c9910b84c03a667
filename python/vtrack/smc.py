"""Sequential Monte Carlo building blocks (the C++ ``core`` layer): the seeded random engine,
log-domain weights, the effective sample size (part-based paper eq. 7), the four resampling
schemes, and Gaussians.

>>> import numpy as np
>>> from vtrack import smc
>>> w, log_z = smc.normalize_log_weights(np.log([0.1, 0.2, 0.7]))
>>> smc.effective_sample_size(w)  # 1 / sum(w**2)
1.8518518518518516
>>> smc.resample(w, smc.Rng(seed=1), method="systematic")
array([1, 2, 2])
"""

from ._core import (
    Gaussian,
    Rng,
    effective_sample_size,
    log_sum_exp,
    normalize_log_weights,
    resample,
)

RESAMPLING_METHODS = ("multinomial", "stratified", "systematic", "residual")

__all__ = [
    "Gaussian",
    "RESAMPLING_METHODS",
    "Rng",
    "effective_sample_size",
    "log_sum_exp",
    "normalize_log_weights",
    "resample",
]

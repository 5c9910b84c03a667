"""Sequential Monte Carlo: the particle filters on vtrack's SMC engine (particle-filters-human-vehicle
§1.2-1.3, part-based-graphical-model-pf Section 2) and their building blocks (the C++ ``core``
layer): the seeded random engine, log-domain weights, the effective sample size (part-based paper
eq. 7), the four resampling schemes, and Gaussians.

``ParticleFilter`` is sequential importance resampling with selective resampling (eq. 7) and
optional resample-move; ``MCMCParticleFilter`` samples each posterior with a Metropolis-Hastings
chain. Models are arguments: the built-in motion models of ``vtrack.models`` (``RandomWalk``,
``ConstantVelocity``, ``SecondOrderAutoRegressive``, ``LinearGaussianMotion``) and observation
models (``LinearGaussianObservation``, ``RangeBearingObservation``), or a Python object with
vectorised ``propagate(particles, rng)`` and/or ``log_likelihood(particles, z)`` methods, called
once per step on the whole (N, d) particle array. See docs/smc.md for the engine's design and how
to write a model.

>>> import numpy as np, vtrack
>>> from vtrack import smc
>>> from vtrack.models import ConstantVelocity, RangeBearingObservation
>>> pf = smc.ParticleFilter(ConstantVelocity(q=0.25), RangeBearingObservation(),
...                         prior=smc.Gaussian([120, 1, 60, 1.5], np.diag([25, 1, 25, 1])),
...                         n_particles=10_000, seed=0)
>>> estimate = pf.step([134.0, 0.46])      # [range, bearing] -> weighted mean [px, vx, py, vy]
>>> pf.particles.shape
(10000, 4)
>>> w, log_z = smc.normalize_log_weights(np.log([0.1, 0.2, 0.7]))
>>> smc.effective_sample_size(w)  # 1 / sum(w**2)
1.8518518518518516
>>> smc.resample(w, smc.Rng(seed=1), method="systematic")
array([1, 2, 2])
"""

from ._core import (
    Gaussian,
    MCMCParticleFilter,
    ParticleFilter,
    Rng,
    effective_sample_size,
    log_sum_exp,
    normalize_log_weights,
    resample,
)

RESAMPLING_METHODS = ("multinomial", "stratified", "systematic", "residual")

__all__ = [
    "Gaussian",
    "MCMCParticleFilter",
    "ParticleFilter",
    "RESAMPLING_METHODS",
    "Rng",
    "effective_sample_size",
    "log_sum_exp",
    "normalize_log_weights",
    "resample",
]

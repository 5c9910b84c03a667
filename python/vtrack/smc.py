"""Particle filters on vtrack's SMC engine (particle-filters-human-vehicle §1.2-1.3,
part-based-graphical-model-pf Section 2).

``ParticleFilter`` is sequential importance resampling with selective resampling (eq. 7) and
optional resample-move; ``MCMCParticleFilter`` samples each posterior with a Metropolis-Hastings
chain. Models are arguments: the built-in motion models (``RandomWalk``, ``ConstantVelocity``,
``SecondOrderAutoRegressive``, ``LinearGaussianMotion``) and observation models
(``LinearGaussianObservation``, ``RangeBearingObservation``), or a Python object with vectorised
``propagate(particles, rng)`` and/or ``log_likelihood(particles, z)`` methods, called once per
step on the whole (N, d) particle array.

>>> import numpy as np, vtrack
>>> pf = vtrack.ParticleFilter(vtrack.ConstantVelocity(q=0.25), vtrack.RangeBearingObservation(),
...                            prior=vtrack.Gaussian([120, 1, 60, 1.5], np.diag([25, 1, 25, 1])),
...                            n_particles=10_000, seed=0)
>>> estimate = pf.step([134.0, 0.46])      # [range, bearing] -> weighted mean [px, vx, py, vy]
>>> pf.particles.shape
(10000, 4)

See docs/smc.md for the engine's design and how to write a model.
"""

from ._core import (
    ConstantVelocity,
    LinearTransition,
    MCMCParticleFilter,
    ParticleFilter,
    RandomWalk,
    RangeBearingObservation,
    SecondOrderAutoRegressive,
)

__all__ = [
    "ConstantVelocity",
    "LinearTransition",
    "MCMCParticleFilter",
    "ParticleFilter",
    "RandomWalk",
    "RangeBearingObservation",
    "SecondOrderAutoRegressive",
]

"""vtrack: Bayesian visual multi-object tracking.

The filters of four papers in C++ with this Python API. Built so far: kernel-density background
subtraction with a multi-Bernoulli track-before-detect tracker (mb-tbd paper), and a labelled
RFS (delta-GLMB) tracker with Murty's ranked assignments and the RGB-D switching observation
model, plus a box tracker for any detector's output, and generic SIR / MCMC particle filters.

The main entry points are here; the rest lives in submodules that mirror the C++ layers:

============================  =========================================================
``vtrack.pipelines``          :func:`track_video`, :func:`track_detections`, :func:`follow`
                              (also here)
``vtrack.trackers``           ``MultiBernoulliTracker``, ``ReclusteringSirTracker``, ``GlmbTracker``,
                              ``BoxTracker``, ``Tracks``; single-object ``ColorParticleTracker``,
                              ``PartParticleTracker`` (also here)
``vtrack.image``              ``KdeBackground``, morphology, integral images, color histograms
``vtrack.detectors``          ``HogPeopleDetector``
``vtrack.models``             motion / observation models, the depth likelihood
``vtrack.smc``                ``ParticleFilter``, ``MCMCParticleFilter`` (also here); random
                              engine, weights, ESS, resampling, Gaussians
``vtrack.assign``             linear assignment, Murty, Gibbs assignments
``vtrack.metrics``            OSPA, OSPA(2), GOSPA (CLEAR-MOT/IDF1/HOTA: ``vtrack.evaluate``)
``vtrack.io``                 MOTChallenge files, config files, video probing
``vtrack.vehicles``           road camera, vehicle ray observation, class prior
``vtrack.synthetic``, ``vtrack.scenarios``, ``vtrack.rgbd``, ``vtrack.synthetic_road``,
``vtrack.synthetic_occlusion``: scenes with exact ground truth; ``vtrack.detsim``: a simulated
detector on real trajectories
============================  =========================================================

Every component takes keyword parameters with the papers' defaults -- the names config files and
``vtrack track --set`` take -- has ``default_params()`` and ``.params``, and rejects an unknown
or wrongly typed keyword with a ``TypeError`` naming it. Every multi-object tracker's ``step``
returns a :class:`Tracks`.

>>> import vtrack
>>> rows = vtrack.track_video("vtest.avi", method="mb", seed=0)        # doctest: +SKIP
>>> rows = vtrack.track_video("vtest.avi", method="glmb", detector="hog")  # doctest: +SKIP

NumPy arrays go in and out without copies where the layout allows; wrong dtypes raise
``TypeError``, wrong shapes or values ``ValueError`` (C++ errors arrive as
``vtrack.InvalidArgument``, a ``ValueError``, and ``vtrack.IoError``, an ``OSError``).
"""

from ._core import (
    BoxTracker,
    ColorParticleTracker,
    Gaussian,
    GlmbTracker,
    HogPeopleDetector,
    InvalidArgument,
    InvalidType,
    IoError,
    KdeBackground,
    LinearGaussianMotion,
    LinearGaussianObservation,
    MCMCParticleFilter,
    MultiBernoulliTracker,
    ParticleFilter,
    PartParticleTracker,
    ReclusteringSirTracker,
    Rng,
    Tracks,
    __version__,
)
from . import assign, detectors, image, io, metrics, models, pipelines, smc, trackers  # noqa: E402
from . import detsim, rgbd, scenarios, synthetic, synthetic_occlusion, synthetic_road, vehicles  # noqa: E402,E501
from .io import load_config  # noqa: E402
from .pipelines import follow, track_detections, track_video  # noqa: E402

__all__ = [
    "BoxTracker",
    "ColorParticleTracker",
    "Gaussian",
    "GlmbTracker",
    "HogPeopleDetector",
    "InvalidArgument",
    "InvalidType",
    "IoError",
    "KdeBackground",
    "LinearGaussianMotion",
    "LinearGaussianObservation",
    "MCMCParticleFilter",
    "MultiBernoulliTracker",
    "ParticleFilter",
    "PartParticleTracker",
    "ReclusteringSirTracker",
    "Rng",
    "Tracks",
    "__version__",
    "assign",
    "detectors",
    "detsim",
    "follow",
    "image",
    "io",
    "load_config",
    "metrics",
    "models",
    "pipelines",
    "rgbd",
    "scenarios",
    "smc",
    "synthetic",
    "synthetic_occlusion",
    "synthetic_road",
    "track_detections",
    "track_video",
    "trackers",
    "vehicles",
]

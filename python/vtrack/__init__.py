"""vtrack: Bayesian visual multi-object tracking.

The filters of four papers -- KDE background subtraction with a multi-Bernoulli
track-before-detect tracker, SIR/MCMC particle filters, a GLMB tracker with Murty's ranked
assignments, and colour/part-based particle filters -- in C++ with this Python API.

This release holds the SMC core the trackers are built from, the KDE background model
(``KdeBackground``, paper eqs. 6-10) that turns video frames into the grey image y, and the
multi-Bernoulli track-before-detect tracker that consumes y (H x W float32, near 1 =
background): ``vtrack.MultiBernoulliTracker((width, height), seed=1)`` and ``.step(y)`` per
frame; ``vtrack.mot`` writes MOTChallenge files, ``python -m vtrack.evaluate`` scores them,
``vtrack.synthetic`` makes scenes with exact ground truth. Colour histograms (part-based paper
eqs. 9-11): ``hsv_histogram``, ``bhattacharyya_coefficient``, ``colour_log_likelihood`` and
``ColourModel``, which scores many boxes against a template in one call;
``vtrack.synthetic_occlusion`` makes a partial-occlusion scene with exact part boxes.
``vtrack.GlmbTracker`` is the labelled RFS tracker (delta-GLMB with Gaussian or particle track
densities, scenarios in ``vtrack.scenarios``), built on ``linear_assignment``, Murty's k-best
``murty`` and the Gibbs sampler ``gibbs_assignments``; with ``particles=`` and a
``DepthLikelihood`` it is the RGB-D switching-observation tracker (``step(detections,
depth=...)``, Kinect conversion ``kinect_raw_to_depth``, synthetic scenes in ``vtrack.rgbd``);
``ospa``, ``ospa2`` and ``gospa`` score it.

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
    bhattacharyya_coefficient,
    bhattacharyya_distance,
    bgr_to_rgi,
    BoxTracker,
    close_square,
    ColourModel,
    colour_log_likelihood,
    DepthLikelihood,
    effective_sample_size,
    foreground_mask,
    Gaussian,
    gibbs_assignments,
    GlmbEstimate,
    GlmbTracker,
    gospa,
    GospaResult,
    HogPeopleDetector,
    hsv_bins,
    hsv_histogram,
    IntegralImage,
    InvalidArgument,
    IoError,
    KdeBackground,
    kinect_depth_to_raw,
    kinect_raw_to_depth,
    linear_assignment,
    LinearGaussianMotion,
    LinearGaussianObservation,
    log_sum_exp,
    MultiBernoulliTracker,
    murty,
    normalize_log_weights,
    ospa,
    ospa2,
    OspaResult,
    probe_video,
    read_detections,
    resample,
    Rng,
    Track,
    track_detections,
    track_video,
    VideoInfo,
    __version__,
)

# Pure-Python modules built on the compiled ones above.
from . import mot, rgbd, scenarios, synthetic, synthetic_occlusion  # noqa: E402

RESAMPLING_METHODS = ("multinomial", "stratified", "systematic", "residual")

__all__ = [
    "BernoulliComponent",
    "bhattacharyya_coefficient",
    "bhattacharyya_distance",
    "bgr_to_rgi",
    "BoxTracker",
    "close_square",
    "ColourModel",
    "colour_log_likelihood",
    "DepthLikelihood",
    "effective_sample_size",
    "foreground_mask",
    "Gaussian",
    "gibbs_assignments",
    "GlmbEstimate",
    "GlmbTracker",
    "gospa",
    "GospaResult",
    "HogPeopleDetector",
    "hsv_bins",
    "hsv_histogram",
    "IntegralImage",
    "InvalidArgument",
    "IoError",
    "KdeBackground",
    "kinect_depth_to_raw",
    "kinect_raw_to_depth",
    "linear_assignment",
    "LinearGaussianMotion",
    "LinearGaussianObservation",
    "log_sum_exp",
    "mot",
    "MultiBernoulliTracker",
    "murty",
    "normalize_log_weights",
    "ospa",
    "ospa2",
    "OspaResult",
    "probe_video",
    "read_detections",
    "resample",
    "RESAMPLING_METHODS",
    "rgbd",
    "Rng",
    "scenarios",
    "synthetic",
    "synthetic_occlusion",
    "Track",
    "track_detections",
    "track_video",
    "VideoInfo",
    "__version__",
]

"""Type stubs for the compiled module vtrack._core (use the public names in `vtrack`)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

class InvalidArgument(ValueError): ...
class IoError(OSError): ...

ArrayLike = npt.ArrayLike
RngLike = Union["Rng", int]

# ---- core ---------------------------------------------------------------------------------------

class Rng:
    def __init__(self, seed: int = 0, stream: int = 0) -> None: ...
    def uniform(self, size: int) -> npt.NDArray[np.float64]: ...
    def normal(self, size: int) -> npt.NDArray[np.float64]: ...
    def next_uint64(self) -> int: ...
    def jump(self) -> None: ...

def log_sum_exp(log_weights: ArrayLike) -> float: ...
def normalize_log_weights(log_weights: ArrayLike) -> Tuple[npt.NDArray[np.float64], float]: ...
def effective_sample_size(weights: ArrayLike, *, log: bool = False) -> float: ...
def resample(
    weights: ArrayLike,
    rng: RngLike,
    count: Optional[int] = None,
    method: Literal["multinomial", "stratified", "systematic", "residual"] = "systematic",
) -> npt.NDArray[np.int64]: ...

class Gaussian:
    def __init__(self, mean: ArrayLike, cov: ArrayLike) -> None: ...
    @property
    def dim(self) -> int: ...
    @property
    def mean(self) -> npt.NDArray[np.float64]: ...
    @property
    def cov(self) -> npt.NDArray[np.float64]: ...
    @property
    def cholesky(self) -> npt.NDArray[np.float64]: ...
    @overload
    def sample(self, rng: RngLike, n: None = None) -> npt.NDArray[np.float64]: ...
    @overload
    def sample(self, rng: RngLike, n: int) -> npt.NDArray[np.float64]: ...
    def log_pdf(self, x: ArrayLike) -> Union[float, npt.NDArray[np.float64]]: ...

# ---- image --------------------------------------------------------------------------------------

def bgr_to_rgi(frame: npt.NDArray[np.uint8]) -> npt.NDArray[np.float32]: ...

class KdeBackground:
    """KDE background model on rgI (mb-tbd paper eqs. 6-10); y near 1 = background."""

    def __init__(
        self,
        *,
        n_samples: int = 10,
        period: int = 10,
        bandwidth: ArrayLike = (0.03, 0.03, 0.06),
        closing: int = 5,
        threads: int = 0,
        update_threshold: float = 0.5,
        update_max_skips: int = 3,
        illumination_compensation: bool = False,
    ) -> None: ...
    def apply(self, frame: npt.NDArray[np.uint8]) -> npt.NDArray[np.float32]: ...
    def freeze(self) -> None: ...
    def resume(self) -> None: ...
    def reset(self) -> None: ...
    @property
    def learning(self) -> bool: ...
    @property
    def frame_index(self) -> int: ...
    @property
    def sample_frames(self) -> List[int]: ...
    @property
    def n_samples(self) -> int: ...
    @property
    def period(self) -> int: ...
    @property
    def bandwidth(self) -> Tuple[float, float, float]: ...
    @property
    def closing(self) -> int: ...
    @property
    def threads(self) -> int: ...
    @property
    def update_threshold(self) -> float: ...
    @property
    def update_max_skips(self) -> int: ...
    @property
    def illumination_compensation(self) -> bool: ...

def foreground_mask(y: npt.NDArray[np.float32], *, threshold: float) -> npt.NDArray[np.uint8]: ...
def close_square(
    image: npt.NDArray[np.float32], size: int, *, threads: int = 0
) -> npt.NDArray[np.float32]: ...

class IntegralImage:
    def __init__(self, image: npt.NDArray[Union[np.uint8, np.float32, np.float64]]) -> None: ...
    @property
    def shape(self) -> Tuple[int, int]: ...
    def sum(self, x: int, y: int, width: int, height: int) -> float: ...
    def area(self, x: int, y: int, width: int, height: int) -> int: ...
    def sums(self, rects: ArrayLike) -> npt.NDArray[np.float64]: ...

# ---- colour histograms (part-based paper section 3.1, eqs. 9-11) --------------------------------

Box = Union[Sequence[float], npt.NDArray[np.float64]]

def hsv_bins(
    frame: npt.NDArray[np.uint8], *, bins: Tuple[int, int, int] = (16, 4, 4)
) -> npt.NDArray[np.uint16]: ...
def hsv_histogram(
    frame: npt.NDArray[np.uint8], box: Box, *, bins: Tuple[int, int, int] = (16, 4, 4),
    kernel: bool = False,
) -> npt.NDArray[np.float64]: ...
def bhattacharyya_coefficient(p: ArrayLike, q: ArrayLike) -> float: ...
def bhattacharyya_distance(p: ArrayLike, q: ArrayLike) -> float: ...
@overload
def colour_log_likelihood(rho: float, *, sigma: float = ...) -> float: ...
@overload
def colour_log_likelihood(rho: npt.NDArray[np.float64], *, sigma: float = ...) -> npt.NDArray[np.float64]: ...

class ColourModel:
    """Template colour histogram and batch Bhattacharyya scoring of (N, 4) boxes (eqs. 9-11)."""

    def __init__(
        self, frame: npt.NDArray[np.uint8], box: Box, *, bins: Tuple[int, int, int] = (16, 4, 4),
        kernel: bool = False,
    ) -> None: ...
    @staticmethod
    def from_histogram(hist: ArrayLike, *, kernel: bool = False) -> "ColourModel": ...
    @property
    def reference(self) -> npt.NDArray[np.float64]: ...
    @property
    def bins(self) -> Tuple[int, int, int]: ...
    @property
    def kernel(self) -> bool: ...
    def coefficients(
        self, frame: npt.NDArray[np.uint8], boxes: ArrayLike, *,
        method: Literal["auto", "direct", "incremental"] = "auto",
    ) -> npt.NDArray[np.float64]: ...
    def log_likelihood(
        self, frame: npt.NDArray[np.uint8], boxes: ArrayLike, *, sigma: float = ...
    ) -> npt.NDArray[np.float64]: ...

# ---- models -------------------------------------------------------------------------------------

class LinearGaussianMotion:
    def __init__(self, F: ArrayLike, Q: ArrayLike) -> None: ...
    @staticmethod
    def constant_velocity(
        axes: int = 2, period: float = 1.0, sigma_v: float = 5.0
    ) -> LinearGaussianMotion: ...
    @property
    def F(self) -> npt.NDArray[np.float64]: ...
    @property
    def Q(self) -> npt.NDArray[np.float64]: ...

class LinearGaussianObservation:
    def __init__(self, H: ArrayLike, R: ArrayLike) -> None: ...
    @staticmethod
    def position(axes: int = 2, R: ArrayLike = ...) -> LinearGaussianObservation: ...
    @property
    def H(self) -> npt.NDArray[np.float64]: ...
    @property
    def R(self) -> npt.NDArray[np.float64]: ...

def kinect_raw_to_depth(raw: ArrayLike, fx: ArrayLike = 525.0) -> Any: ...
def kinect_depth_to_raw(depth: ArrayLike, fx: ArrayLike = 525.0) -> Any: ...

class DepthLikelihood:
    def __init__(
        self,
        width: int,
        height: int,
        fx: float,
        fy: Optional[float] = None,
        cx: Optional[float] = None,
        cy: Optional[float] = None,
        *,
        person_size: Tuple[float, float] = (0.5, 1.7),
        sigma_target: float = 1.0,
        sigma_background: float = 1.0,
        tempering: float = 3e-4,
        min_depth: float = 0.1,
    ) -> None: ...
    def footprint(self, position: ArrayLike) -> Tuple[int, int, int, int]: ...
    def log_ratio(
        self, depth: npt.NDArray[Union[np.float32, np.float64]], positions: ArrayLike
    ) -> npt.NDArray[np.float64]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def fx(self) -> float: ...
    @property
    def fy(self) -> float: ...
    @property
    def cx(self) -> float: ...
    @property
    def cy(self) -> float: ...
    @property
    def person_size(self) -> Tuple[float, float]: ...
    @property
    def sigma_target(self) -> float: ...
    @property
    def sigma_background(self) -> float: ...
    @property
    def tempering(self) -> float: ...

# ---- filters: GLMB ------------------------------------------------------------------------------

class GlmbEstimate:
    @property
    def label(self) -> Tuple[int, int]: ...
    @property
    def mean(self) -> npt.NDArray[np.float64]: ...
    @property
    def cov(self) -> npt.NDArray[np.float64]: ...

class GlmbTracker:
    def __init__(
        self,
        motion: LinearGaussianMotion,
        observation: LinearGaussianObservation,
        births: Sequence[Tuple[float, ArrayLike, ArrayLike]],
        *,
        survival_probability: float = 0.99,
        detection_probability: float = 0.98,
        clutter_intensity: float = 7.5e-6,
        hypothesis_budget: int = 1000,
        max_hypotheses: int = 1000,
        prune_threshold: float = 1e-15,
        gate_threshold: float = 32.24,
        adaptive_birth_cov: Optional[ArrayLike] = None,
        adaptive_birth_rate: float = 0.1,
        adaptive_birth_max_existence: float = 0.03,
        ranking: str = "murty",
        particles: Optional[int] = None,
        depth_model: Optional[DepthLikelihood] = None,
        resample_threshold: float = 0.5,
        seed: int = 0,
        depth_for_births: bool = True,
        mask_detections: bool = True,
        occlusion_margin: float = 0.3,
        occluded_detection_probability: bool = False,
    ) -> None: ...
    def step(
        self, detections: ArrayLike, depth: Optional[npt.NDArray[Union[np.float32, np.float64]]] = None
    ) -> List[GlmbEstimate]: ...
    def estimates(self) -> List[GlmbEstimate]: ...
    def cardinality_distribution(self) -> npt.NDArray[np.float64]: ...
    @property
    def map_cardinality(self) -> int: ...
    @property
    def hypothesis_count(self) -> int: ...
    @property
    def track_count(self) -> int: ...
    @property
    def time(self) -> int: ...
    @property
    def particles(self) -> Optional[int]: ...
    @property
    def has_depth_model(self) -> bool: ...

# ---- filters: assignment and metrics -----------------------------------------------------------

def linear_assignment(
    cost: ArrayLike,
) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]: ...
def murty(cost: ArrayLike, k: int) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]: ...
def gibbs_assignments(
    cost: ArrayLike, sweeps: int, rng: RngLike = 0
) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...

class OspaResult:
    @property
    def distance(self) -> float: ...
    @property
    def localisation(self) -> float: ...
    @property
    def cardinality(self) -> float: ...
    def __float__(self) -> float: ...

class GospaResult:
    @property
    def distance(self) -> float: ...
    @property
    def localisation(self) -> float: ...
    @property
    def missed(self) -> float: ...
    @property
    def false_targets(self) -> float: ...
    @property
    def n_assigned(self) -> int: ...
    @property
    def n_missed(self) -> int: ...
    @property
    def n_false(self) -> int: ...
    def __float__(self) -> float: ...

def ospa(x: ArrayLike, y: ArrayLike, c: float, p: float = 1.0) -> OspaResult: ...
def gospa(truth: ArrayLike, estimates: ArrayLike, c: float, p: float = 1.0) -> GospaResult: ...
def ospa2(x: ArrayLike, y: ArrayLike, c: float, p: float = 1.0) -> OspaResult: ...
# ---- filters ------------------------------------------------------------------------------------

class Track:
    @property
    def label(self) -> int: ...
    @property
    def x(self) -> float: ...
    @property
    def y(self) -> float: ...
    @property
    def w(self) -> float: ...
    @property
    def h(self) -> float: ...
    @property
    def existence(self) -> float: ...
    @property
    def box(self) -> Tuple[float, float, float, float]: ...

class BernoulliComponent:
    @property
    def label(self) -> int: ...
    @property
    def birth_frame(self) -> int: ...
    @property
    def existence(self) -> float: ...
    @property
    def particles(self) -> npt.NDArray[np.float32]: ...
    @property
    def weights(self) -> npt.NDArray[np.float64]: ...
    @property
    def mean(self) -> Tuple[float, float, float, float]: ...

class MultiBernoulliTracker:
    def __init__(
        self,
        image_size: Tuple[int, int],
        *,
        seed: int = 0,
        delta_f: float = ...,
        delta_b: float = ...,
        closing_size: int = ...,
        survival_probability: float = ...,
        sigma_x: float = ...,
        sigma_y: float = ...,
        sigma_w: float = ...,
        sigma_h: float = ...,
        width_mean: float = ...,
        width_std: float = ...,
        height_mean: float = ...,
        height_std: float = ...,
        width_min: float = ...,
        width_max: float = ...,
        height_min: float = ...,
        height_max: float = ...,
        quarter_birth: bool = ...,
        birth_probability: float = ...,
        birth_particles: int = ...,
        adaptive_birth: bool = ...,
        adaptive_birth_probability: float = ...,
        adaptive_birth_log_likelihood: float = ...,
        cover_existence: float = ...,
        established_age: int = ...,
        adaptive_birth_stride: int = ...,
        adaptive_birth_max: int = ...,
        min_particles: int = ...,
        max_particles: int = ...,
        resampling: Literal["multinomial", "stratified", "systematic", "residual"] = ...,
        prune_threshold: float = ...,
        merge_overlap: float = ...,
        estimate_threshold: float = ...,
        max_existence: float = ...,
        confirm_frames: int = ...,
        lost_memory: int = ...,
        relabel_overlap: float = ...,
        velocity_smoothing: float = ...,
        box_scale_w: float = ...,
        box_scale_h: float = ...,
        box_offset_x: float = ...,
        box_offset_y: float = ...,
    ) -> None: ...
    def step(self, y: npt.NDArray[np.float32]) -> List[Track]: ...
    @property
    def tracks(self) -> List[Track]: ...
    @property
    def components(self) -> List[BernoulliComponent]: ...
    @property
    def frame(self) -> int: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

# ---- apps ---------------------------------------------------------------------------------------

class VideoInfo:
    @property
    def frame_count(self) -> int: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def fps(self) -> float: ...
    @property
    def is_image_folder(self) -> bool: ...

def probe_video(path: Union[str, PathLike[str]]) -> VideoInfo: ...

def track_video(
    path: Union[str, PathLike[str]],
    method: Literal["mb"] = "mb",
    *,
    seed: int = 0,
    render: Optional[Union[str, PathLike[str]]] = None,
    background: Optional[Dict[str, Any]] = None,
    **tracker: Any,
) -> npt.NDArray[np.float64]: ...

# ---- detection-driven tracking ------------------------------------------------------------------

def read_detections(
    path: Union[str, PathLike[str]], min_confidence: float = ...
) -> npt.NDArray[np.float64]: ...

def track_detections(
    detections: Union[str, PathLike[str], ArrayLike],
    image_size: Optional[Tuple[float, float]] = None,
    *,
    last_frame: int = 0,
    detection_probability: float = ...,
    survival_probability: float = ...,
    outside_survival_probability: float = ...,
    outside_detection_probability: float = ...,
    clutter_rate: float = ...,
    sigma_accel: float = ...,
    sigma_size: float = ...,
    detection_sd_centre: float = ...,
    detection_sd_size: float = ...,
    birth_sd_centre: float = ...,
    birth_sd_velocity: float = ...,
    birth_sd_size: float = ...,
    birth_rate: float = ...,
    birth_max_existence: float = ...,
    hypothesis_budget: int = ...,
    gate_threshold: float = ...,
    min_confidence: float = ...,
    min_age: int = ...,
    gibbs_ranking: bool = ...,
    seed: int = ...,
) -> npt.NDArray[np.float64]: ...

class BoxTracker:
    def __init__(
        self,
        image_size: Tuple[float, float],
        *,
        detection_probability: float = ...,
        survival_probability: float = ...,
        outside_survival_probability: float = ...,
        outside_detection_probability: float = ...,
        clutter_rate: float = ...,
        sigma_accel: float = ...,
        sigma_size: float = ...,
        detection_sd_centre: float = ...,
        detection_sd_size: float = ...,
        birth_sd_centre: float = ...,
        birth_sd_velocity: float = ...,
        birth_sd_size: float = ...,
        birth_rate: float = ...,
        birth_max_existence: float = ...,
        hypothesis_budget: int = ...,
        gate_threshold: float = ...,
        min_confidence: float = ...,
        min_age: int = ...,
        gibbs_ranking: bool = ...,
        seed: int = ...,
    ) -> None: ...
    def step(self, boxes: ArrayLike) -> npt.NDArray[np.float64]: ...
    @property
    def frame(self) -> int: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

class HogPeopleDetector:
    def __init__(
        self,
        *,
        hit_threshold: float = ...,
        win_stride: int = ...,
        padding: int = ...,
        scale: float = ...,
        upscale: float = ...,
        group_threshold: int = ...,
        min_score: float = ...,
        person_fraction: float = ...,
    ) -> None: ...
    def detect(self, frame: npt.NDArray[np.uint8]) -> npt.NDArray[np.float64]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

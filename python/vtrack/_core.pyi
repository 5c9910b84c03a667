"""Type stubs for the compiled module vtrack._core (use the public names in `vtrack`)."""

from os import PathLike
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

class InvalidArgument(ValueError): ...
class InvalidType(TypeError): ...
class IoError(OSError): ...

ArrayLike = npt.ArrayLike
RngLike = Union["Rng", int]

# ---- the one estimate type --------------------------------------------------------------------

class Tracks:
    """What every multi-object tracker's step() returns (see vtrack.trackers)."""

    @property
    def ids(self) -> npt.NDArray[np.int64]: ...
    @property
    def boxes(self) -> npt.NDArray[np.float64]: ...
    @property
    def scores(self) -> npt.NDArray[np.float64]: ...
    @property
    def states(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def covariances(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def labels(self) -> Optional[npt.NDArray[np.int64]]: ...
    def __len__(self) -> int: ...

def mot_rows(frame: int, tracks: Tracks) -> npt.NDArray[np.float64]: ...
def write_mot(path: Union[str, PathLike[str]], rows: ArrayLike) -> None: ...

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
        bandwidth: Tuple[float, float, float] = (0.03, 0.03, 0.06),
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
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

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
        person_width: float = 0.5,
        person_height: float = 1.7,
        sigma_target: float = 1.0,
        sigma_background: float = 1.0,
        tempering: float = 0.0003,
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
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

# ---- filters: GLMB ------------------------------------------------------------------------------

class GlmbTracker:
    def __init__(
        self,
        motion: LinearGaussianMotion,
        observation: LinearGaussianObservation,
        births: Sequence[Tuple[float, ArrayLike, ArrayLike]],
        *,
        adaptive_birth_cov: Optional[ArrayLike] = None,
        depth_model: Optional[DepthLikelihood] = None,
        survival_probability: float = 0.99,
        detection_probability: float = 0.98,
        clutter_intensity: float = 7.5e-06,
        hypothesis_budget: int = 1000,
        max_hypotheses: int = 1000,
        prune_threshold: float = 1e-15,
        gate_threshold: float = 32.24,
        adaptive_birth_rate: float = 0.1,
        adaptive_birth_max_existence: float = 0.03,
        ranking: Literal["murty", "gibbs"] = 'murty',
        seed: int = 0,
        densities: Literal["gaussian", "particles"] = 'gaussian',
        n_particles: int = 500,
        resample_threshold: float = 0.5,
        depth_for_births: bool = True,
        mask_detections: bool = True,
        occlusion_margin: float = 0.3,
        occluded_detection_probability: bool = False,
        confirm_frames: int = 1,
        lost_memory: int = 0,
        relabel_overlap: float = 0.3,
    ) -> None: ...
    def step(
        self, detections: ArrayLike, depth: Optional[npt.NDArray[Union[np.float32, np.float64]]] = None
    ) -> Tracks: ...
    @property
    def tracks(self) -> Tracks: ...
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
    def has_depth_model(self) -> bool: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

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
        delta_f: float = 0.1,
        delta_b: float = 0.002,
        closing_size: int = 0,
        survival_probability: float = 0.99,
        sigma_x: float = 5.0,
        sigma_y: float = 5.0,
        sigma_w: float = 1.5,
        sigma_h: float = 2.0,
        width_mean: float = 30.0,
        width_std: float = 8.0,
        height_mean: float = 85.0,
        height_std: float = 20.0,
        width_min: float = 12.0,
        width_max: float = 64.0,
        height_min: float = 40.0,
        height_max: float = 150.0,
        quarter_birth: bool = True,
        birth_probability: float = 0.02,
        birth_particles: int = 200,
        cover_existence: float = 0.1,
        established_age: int = 3,
        adaptive_birth: bool = True,
        adaptive_birth_probability: float = 0.05,
        adaptive_birth_log_likelihood: float = -3.0,
        adaptive_birth_stride: int = 8,
        adaptive_birth_max: int = 3,
        min_particles: int = 50,
        max_particles: int = 400,
        resampling: Literal["multinomial", "stratified", "systematic", "residual"] = 'systematic',
        prune_threshold: float = 0.01,
        merge_overlap: float = 0.6,
        estimate_threshold: float = 0.5,
        max_existence: float = 0.999,
        confirm_frames: int = 5,
        lost_memory: int = 30,
        relabel_overlap: float = 0.3,
        velocity_smoothing: float = 0.3,
        box_scale_w: float = 1.75,
        box_scale_h: float = 1.47,
        box_offset_x: float = -0.01,
        box_offset_y: float = -0.01,
        seed: int = 0,
    ) -> None: ...
    def step(self, y: npt.NDArray[np.float32]) -> Tracks: ...
    @property
    def tracks(self) -> Tracks: ...
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

def load_config(path: Union[str, PathLike[str]]) -> Dict[str, Any]: ...
def track_video(
    video: Union[str, PathLike[str]],
    method: str,
    detector: str,
    config: Dict[str, Any],
    params: Dict[str, Any],
    render: Optional[Union[str, PathLike[str]]],
    progress: Optional[Callable[[int, int], None]],
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], int]: ...

# ---- detection-driven tracking ------------------------------------------------------------------

def read_detections(
    path: Union[str, PathLike[str]], min_confidence: float = ...
) -> npt.NDArray[np.float64]: ...

def track_detections(
    detections: Union[str, PathLike[str], ArrayLike],
    image_size: Optional[Tuple[int, int]],
    last_frame: int,
    params: Dict[str, Any],
    progress: Optional[Callable[[int, int], None]],
) -> npt.NDArray[np.float64]: ...

class BoxTracker:
    def __init__(
        self,
        image_size: Tuple[int, int],
        *,
        detection_probability: float = 0.8,
        survival_probability: float = 0.99,
        outside_survival_probability: float = 0.1,
        outside_detection_probability: float = 0.1,
        clutter_rate: float = 1.0,
        sigma_accel: float = 2.0,
        sigma_size: float = 1.0,
        detection_sd_centre: float = 8.0,
        detection_sd_size: float = 10.0,
        birth_sd_centre: float = 10.0,
        birth_sd_velocity: float = 5.0,
        birth_sd_size: float = 10.0,
        birth_rate: float = 0.5,
        birth_max_existence: float = 0.3,
        hypothesis_budget: int = 200,
        gate_threshold: float = 38.24,
        min_confidence: float = ...,
        confirm_frames: int = 1,
        lost_memory: int = 0,
        relabel_overlap: float = 0.3,
        ranking: Literal["murty", "gibbs"] = 'murty',
        seed: int = 0,
    ) -> None: ...
    def step(self, boxes: ArrayLike) -> Tracks: ...
    @property
    def frame(self) -> int: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

class HogPeopleDetector:
    def __init__(
        self,
        *,
        hit_threshold: float = 0.0,
        win_stride: int = 8,
        padding: int = 8,
        scale: float = 1.1,
        upscale: float = 1.5,
        group_threshold: int = 2,
        min_score: float = 0.0,
        person_fraction: float = 0.75,
    ) -> None: ...
    def detect(self, frame: npt.NDArray[np.uint8]) -> npt.NDArray[np.float64]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

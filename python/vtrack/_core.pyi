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
        closing: int = 3,
        threads: int = 0,
        update_threshold: float = 0.5,
        update_max_skips: int = 3,
        update_static: bool = False,
        illumination_compensation: bool = False,
    ) -> None: ...
    def apply(self, frame: npt.NDArray[np.uint8]) -> npt.NDArray[np.float32]: ...
    def set_closing(self, size: int) -> None: ...
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

# ---- color histograms (part-based paper section 3.1, eqs. 9-11) --------------------------------

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
def color_log_likelihood(rho: float, *, sigma: float = ...) -> float: ...
@overload
def color_log_likelihood(rho: npt.NDArray[np.float64], *, sigma: float = ...) -> npt.NDArray[np.float64]: ...

class ColorModel:
    """Template color histogram and batch Bhattacharyya scoring of (N, 4) boxes (eqs. 9-11)."""

    def __init__(
        self, frame: npt.NDArray[np.uint8], box: Box, *, bins: Tuple[int, int, int] = (16, 4, 4),
        kernel: bool = False,
    ) -> None: ...
    @staticmethod
    def from_histogram(hist: ArrayLike, *, kernel: bool = False) -> "ColorModel": ...
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

class ForegroundSizeEstimator:
    def __init__(
        self, *, half_life: float = ..., min_area_fraction: float = 1e-4, aspect: float = 0.35
    ) -> None: ...
    def observe(self, y: npt.NDArray[np.float32], *, threshold: float = 0.5) -> None: ...
    @property
    def person_height(self) -> float: ...
    @property
    def person_height_line(self) -> Dict[str, Any]: ...
    @property
    def weight(self) -> float: ...
    @property
    def frames(self) -> int: ...
    def reset(self) -> None: ...

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
        gate_max_detections: int = 50,
        adaptive_birth_rate: float = 0.1,
        adaptive_birth_max_existence: float = 0.03,
        adaptive_birth_max: int = 100,
        adaptive_birth_missed_tracks: bool = False,
        occlusion_rate: float = 0.0,
        occlusion_length: float = 10.0,
        occlusion_max_length: int = 1000,
        label_estimator: Literal["map", "consistent"] = 'consistent',
        label_keep_bonus: float = 2.0,
        label_entry_penalty: float = 0.0,
        label_duplicate_gate: float = 0.0,
        ranking: Literal["murty", "gibbs"] = 'murty',
        seed: int = 0,
        densities: Literal["gaussian", "particles"] = 'gaussian',
        n_particles: int = 500,
        resample_threshold: float = 0.5,
        regularise: bool = True,
        depth_for_births: bool = True,
        mask_detections: bool = True,
        occlusion_margin: float = 0.3,
        mask_depth_margin: float = 0.3,
        track_occluders: bool = False,
        occluded_detection_probability: bool = False,
        confirm_frames: int = 1,
        lost_memory: int = 0,
        relabel_overlap: float = 0.3,
        relabel_distance: float = 0.0,
        appearance_rate: float = 0.0,
        appearance_sigma: float = 0.3,
        appearance_distance: float = 3.0,
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
        delta_b_row: float = 0.52,
        delta_b_no_line: float = 0.2,
        delta_b_reference: Literal["person", "image", "row"] = 'row',
        closing_size: int = 0,
        closing_ratio: float = 0.06,
        survival_probability: float = 0.99,
        height_mean: float = 0.0,
        size_aspect: float = 0.35,
        size_from_foreground: float = 1.06,
        size_initial: float = 0.15,
        size_half_life: float = 0.0,
        size_std: float = 0.25,
        size_min: float = 0.45,
        size_max: float = 2.0,
        width_mean: float = 0.0,
        size_by_row: bool = True,
        sigma_xy: float = 0.06,
        sigma_wh: float = 0.02,
        quarter_birth: bool = True,
        birth_probability: float = 0.02,
        birth_particles: int = 200,
        cover_existence: float = 0.1,
        established_age: int = 3,
        adaptive_birth: bool = True,
        adaptive_birth_probability: float = 0.05,
        adaptive_birth_log_likelihood: float = -3.0,
        adaptive_birth_stride: float = 0.1,
        adaptive_birth_max: int = 3,
        min_particles: int = 50,
        max_particles: int = 1600,
        resampling: Literal["multinomial", "stratified", "systematic", "residual"] = 'systematic',
        prune_threshold: float = 0.01,
        merge_overlap: float = 0.6,
        estimate_threshold: float = 0.5,
        max_existence: float = 0.999,
        confirm_frames: int = 5,
        lost_memory: int = 30,
        relabel_overlap: float = 0.3,
        relabel_distance: float = 3.0,
        appearance_rate: float = 0.05,
        appearance_sigma: float = 0.15,
        appearance_distance: float = 1.5,
        velocity_smoothing: float = 0.3,
        box_scale_w: float = 1.673,
        box_scale_h: float = 1.706,
        box_offset_x: float = 0.023,
        box_offset_y: float = 0.045,
        box_clip: bool = True,
        seed: int = 0,
    ) -> None: ...
    def step(
        self, y: npt.NDArray[np.float32], frame: Optional[npt.NDArray[np.uint8]] = None
    ) -> Tracks: ...
    @property
    def tracks(self) -> Tracks: ...
    @property
    def components(self) -> List[BernoulliComponent]: ...
    @property
    def frame(self) -> int: ...
    @property
    def closing_pixels(self) -> int: ...
    @property
    def size_prior(self) -> Dict[str, Any]: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

class ReclusteringSirTracker:
    def __init__(
        self,
        image_size: Tuple[int, int],
        *,
        n_particles: int = 600,
        budget_objects: int = 4,
        resampling: Literal["multinomial", "stratified", "systematic", "residual"] = 'systematic',
        rho: float = 0.1,
        novelty_sigma: float = 0.35,
        shape_weight: float = 0.1,
        foreground_threshold: float = 0.5,
        grid_step: float = 0.05,
        gate: float = 1.5,
        novelty_threshold: float = 0.5,
        inject_fraction: float = 0.1,
        min_object_fraction: float = 0.3,
        keep_fraction: float = 0.3,
        merge_distance: float = 1.2,
        merge_size: float = 1.3,
        merge_velocity: float = 0.08,
        max_misses: int = 3,
        height_mean: float = 0.0,
        size_aspect: float = 0.35,
        size_from_foreground: float = 1.06,
        size_initial: float = 0.15,
        size_half_life: float = 0.0,
        size_std: float = 0.25,
        size_min: float = 0.45,
        size_max: float = 2.0,
        size_by_row: bool = True,
        sigma_xy: float = 0.03,
        sigma_velocity: float = 0.02,
        sigma_wh: float = 0.04,
        confirm_frames: int = 5,
        lost_memory: int = 30,
        relabel_overlap: float = 0.1,
        relabel_distance: float = 0.0,
        appearance_rate: float = 0.05,
        appearance_sigma: float = 0.15,
        appearance_distance: float = 1.5,
        box_scale_w: float = 1.06,
        box_scale_h: float = 0.93,
        box_offset_x: float = 0.01,
        box_offset_y: float = -0.06,
        box_clip: bool = True,
        seed: int = 0,
    ) -> None: ...
    def step(
        self, y: npt.NDArray[np.float32], frame: Optional[npt.NDArray[np.uint8]] = None
    ) -> Tracks: ...
    @property
    def tracks(self) -> Tracks: ...
    @property
    def particles(self) -> npt.NDArray[np.float32]: ...
    @property
    def clusters(self) -> npt.NDArray[np.int32]: ...
    @property
    def objects(self) -> List[Dict[str, Any]]: ...
    @property
    def frame(self) -> int: ...
    @property
    def person_height(self) -> float: ...
    @property
    def grid_pixels(self) -> int: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

def ellipse_log_likelihood(
    ellipse: ArrayLike,
    points: ArrayLike,
    rho: float,
    sigma: ArrayLike,
    shape_power: float = 1.0,
) -> float: ...

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
def pipeline_params(
    method: str,
    detector: str,
    config: Dict[str, Any],
    params: Dict[str, Any],
    settings: List[str],
) -> Dict[str, Dict[str, Any]]: ...
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
        sigma_accel: float = 1.0,
        sigma_size: float = 1.0,
        detection_sd_centre: float = 4.0,
        detection_sd_size: float = 4.0,
        birth_sd_centre: float = 10.0,
        birth_sd_velocity: float = 5.0,
        birth_sd_size: float = 10.0,
        birth_rate: float = 0.02,
        birth_max_existence: float = 0.1,
        hypothesis_budget: int = 200,
        gate_threshold: float = 38.24,
        min_confidence: float = ...,
        learn_clutter: bool = True,
        learn_detection_probability: bool = True,
        detection_probability_min: float = 0.3,
        detection_probability_max: float = 0.98,
        learning_memory: float = 100.0,
        learning_prior_weight: float = 10.0,
        use_scores: bool = True,
        score_window: int = 1000,
        birth_score_weight: bool = True,
        duplicate_rate: float = 0.1,
        detection_sd_relative: float = 0.08,
        occlusion_rate: float = 0.03,
        occlusion_length: float = 10.0,
        occlusion_max_length: int = 20,
        label_estimator: Literal["map", "consistent"] = 'map',
        label_keep_bonus: float = 2.0,
        label_entry_penalty: float = 0.0,
        label_duplicate_gate: float = 0.0,
        max_births: int = 100,
        birth_missed_tracks: bool = False,
        confirm_frames: int = 1,
        lost_memory: int = 0,
        relabel_overlap: float = 0.3,
        relabel_distance: float = 0.0,
        appearance_rate: float = 0.0,
        appearance_sigma: float = 0.3,
        appearance_distance: float = 3.0,
        ranking: Literal["murty", "gibbs"] = 'murty',
        seed: int = 0,
    ) -> None: ...
    def step(self, boxes: ArrayLike) -> Tracks: ...
    @property
    def frame(self) -> int: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def learnt(self) -> Dict[str, Any]: ...
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

# ---- vehicles: road camera, ray observation, class prior (particle-filters-human-vehicle §3) -----

class Camera:
    def __init__(
        self,
        K: ArrayLike,
        dist: ArrayLike,
        R: ArrayLike,
        t: ArrayLike,
        *,
        road_axis_world: ArrayLike = [0.0, 1.0, 0.0],
        image_size: Optional[Tuple[int, int]] = None,
    ) -> None: ...
    @property
    def K(self) -> npt.NDArray[np.float64]: ...
    @property
    def dist(self) -> npt.NDArray[np.float64]: ...
    @property
    def R(self) -> npt.NDArray[np.float64]: ...
    @property
    def t(self) -> npt.NDArray[np.float64]: ...
    @property
    def image_size(self) -> Optional[Tuple[int, int]]: ...
    @property
    def has_distortion(self) -> bool: ...
    @property
    def centre(self) -> npt.NDArray[np.float64]: ...
    @property
    def road_axis(self) -> npt.NDArray[np.float64]: ...
    @property
    def lateral_axis(self) -> npt.NDArray[np.float64]: ...
    @property
    def road_to_image_homography(self) -> npt.NDArray[np.float64]: ...
    @property
    def image_to_road_homography(self) -> npt.NDArray[np.float64]: ...
    def project(self, points: ArrayLike) -> npt.NDArray[np.float64]: ...
    def undistort(self, pixels: ArrayLike) -> npt.NDArray[np.float64]: ...
    def rays(self, pixels: ArrayLike) -> npt.NDArray[np.float64]: ...
    def image_to_road(self, pixels: ArrayLike) -> npt.NDArray[np.float64]: ...
    def road_to_image(self, road: ArrayLike) -> npt.NDArray[np.float64]: ...

def read_camera_file(path: Union[str, PathLike]) -> Camera: ...

class VehicleObservation:
    @property
    def road_polygon(self) -> npt.NDArray[np.float64]: ...
    @property
    def box(self) -> Tuple[float, float, float, float]: ...
    @property
    def reference_world(self) -> npt.NDArray[np.float64]: ...
    @property
    def far_corner_world(self) -> npt.NDArray[np.float64]: ...
    @property
    def w_axis_world(self) -> npt.NDArray[np.float64]: ...
    @property
    def l_axis_world(self) -> npt.NDArray[np.float64]: ...
    @property
    def camera_within_width(self) -> bool: ...
    @property
    def camera_within_length(self) -> bool: ...
    @property
    def a(self) -> npt.NDArray[np.float64]: ...
    @property
    def b(self) -> npt.NDArray[np.float64]: ...
    @property
    def plucker(self) -> npt.NDArray[np.float64]: ...
    def to_whl(self, world: ArrayLike) -> npt.NDArray[np.float64]: ...
    def to_world(self, whl: ArrayLike) -> npt.NDArray[np.float64]: ...
    def point_at_height(self, h: float) -> npt.NDArray[np.float64]: ...
    def feasible_heights(self, min_size: ArrayLike) -> Tuple[float, float]: ...
    def project(self, whl: ArrayLike) -> npt.NDArray[np.float64]: ...
    def distance(self, whl: ArrayLike) -> npt.NDArray[np.float64]: ...
    def log_likelihood(
        self, whl: ArrayLike, *, sigma_w: float = 0.25, sigma_h: float = 0.25, sigma_l: float = 0.25
    ) -> npt.NDArray[np.float64]: ...

def observe_vehicle(camera: Camera, silhouette: ArrayLike, *, max_edge_px: float = 4.0) -> VehicleObservation: ...
def table1_vehicle_models() -> List[Dict[str, Any]]: ...
def read_vehicle_models_file(path: Union[str, PathLike]) -> List[Dict[str, Any]]: ...

class VehicleModelPrior:
    def __init__(
        self, models: Optional[List[Dict[str, Any]]] = None, *, min_size: ArrayLike = [0.4, 0.6, 1.0]
    ) -> None: ...
    @property
    def models(self) -> List[Dict[str, Any]]: ...
    @property
    def names(self) -> List[str]: ...
    @property
    def min_size(self) -> npt.NDArray[np.float64]: ...
    def log_density(self, whl: ArrayLike) -> npt.NDArray[np.float64]: ...
    def class_log_posteriors(self, whl: ArrayLike) -> npt.NDArray[np.float64]: ...
    def map_class(self, whl: ArrayLike) -> npt.NDArray[np.int32]: ...

class VehicleDimensionEstimator:
    def __init__(
        self,
        camera: Camera,
        *,
        models: Union[None, List[Dict[str, Any]], str, PathLike] = None,
        sampler: Literal["ray", "mh", "discrete", "rays"] = "rays",
        reference: Literal["all", "random", "map", "mean"] = "map",
        n_particles: int = 100,
        burn_in: int = 50,
        thinning: int = 1,
        proposal_scale: float = 0.2,
        dynamic_sigma: float = 0.3,
        min_size: Tuple[float, float, float] = (0.4, 0.6, 1.0),
        sigma_w: float = 0.25,
        sigma_h: float = 0.25,
        sigma_l: float = 0.25,
        max_edge_px: float = 4.0,
        light_heavy_rule: Literal["volume", "class"] = "volume",
        heavy_volume: float = 45.0,
        heavy_height: float = 3.0,
        max_vehicle_width: float = 2.6,
        decision: Literal["auto", "mean", "last"] = "auto",
        border_margin_px: float = 1.0,
        max_length_resolution: float = 0.0,
        length_resolution_factor: float = 4.0,
        outlier_gate: float = 3.0,
        far_view_gate: float = 3.0,
        seed: int = 0,
    ) -> None: ...
    def update(self, vehicle_id: int, silhouette: ArrayLike, frame: Optional[int] = None) -> bool: ...
    def estimate(self, vehicle_id: int) -> Dict[str, Any]: ...
    def estimates(self) -> List[Dict[str, Any]]: ...
    def posterior(self, vehicle_id: int) -> Optional[Dict[str, Any]]: ...
    @property
    def models(self) -> List[Dict[str, Any]]: ...
    @property
    def camera(self) -> Camera: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

# ---- SMC engine: particle filters and their models (bindings/smc.cpp) --------------------------

# A model written in Python: an object with `dim` (int) and a vectorised
# propagate(particles: (N, d) float64, rng: numpy.random.Generator) -> (N, d) array, and/or a
# vectorised log_likelihood(particles: (N, d) float64, z: (m,) float64) -> (N,) log weights.
_PythonMotion = Any
_PythonObservation = Any

class LinearTransition:
    @property
    def F(self) -> npt.NDArray[np.float64]: ...
    @property
    def Q(self) -> npt.NDArray[np.float64]: ...
    @property
    def noise_factor(self) -> npt.NDArray[np.float64]: ...
    @property
    def dim(self) -> int: ...
    @property
    def noise_dim(self) -> int: ...

class RandomWalk(LinearTransition):
    def __init__(self, sigma: Union[float, ArrayLike] = 1.0, dims: Optional[int] = None) -> None: ...
    @property
    def sigma(self) -> npt.NDArray[np.float64]: ...

class ConstantVelocity(LinearTransition):
    def __init__(
        self,
        axes: int = 2,
        period: float = 1.0,
        q: float = 1.0,
        noise: Literal["continuous", "discrete"] = "continuous",
    ) -> None: ...
    @property
    def axes(self) -> int: ...
    @property
    def period(self) -> float: ...
    @property
    def q(self) -> float: ...
    @property
    def noise(self) -> str: ...

class SecondOrderAutoRegressive(LinearTransition):
    def __init__(self, sigma: Union[float, ArrayLike] = 1.0, dims: Optional[int] = None) -> None: ...

class RangeBearingObservation:
    def __init__(
        self,
        sigma_range: float = 1.0,
        sigma_bearing: float = 0.01,
        sensor: Tuple[float, float] = (0.0, 0.0),
        position: Tuple[int, int] = (0, 2),
    ) -> None: ...
    def log_likelihood(self, particles: ArrayLike, z: ArrayLike) -> npt.NDArray[np.float64]: ...
    @property
    def sigma_range(self) -> float: ...
    @property
    def sigma_bearing(self) -> float: ...
    @property
    def sensor(self) -> Tuple[float, float]: ...
    @property
    def position(self) -> Tuple[int, int]: ...

MotionModel = Union[LinearTransition, LinearGaussianMotion, _PythonMotion]
ObservationModel = Union[LinearGaussianObservation, RangeBearingObservation, _PythonObservation]

class ParticleFilter:
    def __init__(
        self,
        motion: MotionModel,
        observation: ObservationModel,
        *,
        prior: Union[Gaussian, ArrayLike],
        dtype: Literal["float64", "float32"] = "float64",
        n_particles: int = 1000,
        resampling: Literal["multinomial", "stratified", "systematic", "residual"] = "systematic",
        ess_threshold: float = 1.0,
        resample_move_steps: int = 0,
        move_scale: float = 0.5,
        threads: int = 1,
        seed: int = 0,
    ) -> None: ...
    def step(self, z: ArrayLike) -> npt.NDArray[np.float64]: ...
    def predict(self) -> npt.NDArray[np.float64]: ...
    @property
    def particles(self) -> npt.NDArray[np.float64]: ...
    @property
    def weights(self) -> npt.NDArray[np.float64]: ...
    @property
    def log_weights(self) -> npt.NDArray[np.float64]: ...
    @property
    def log_evidence(self) -> float: ...
    @property
    def ess(self) -> float: ...
    @property
    def resampled(self) -> bool: ...
    @property
    def n_particles(self) -> int: ...
    @property
    def dim(self) -> int: ...
    @property
    def mean(self) -> npt.NDArray[np.float64]: ...
    @property
    def map_estimate(self) -> npt.NDArray[np.float64]: ...
    @property
    def acceptance_rate(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

class MCMCParticleFilter:
    def __init__(
        self,
        motion: Union[LinearTransition, LinearGaussianMotion],
        observation: ObservationModel,
        *,
        prior: Gaussian,
        n_particles: int = 1000,
        burn_in: int = 500,
        thinning: int = 2,
        reference: Literal["all", "random", "map", "mean"] = "all",
        proposal_scale: float = 0.5,
        seed: int = 0,
    ) -> None: ...
    def step(self, z: ArrayLike) -> npt.NDArray[np.float64]: ...
    @property
    def particles(self) -> npt.NDArray[np.float64]: ...
    @property
    def log_target(self) -> npt.NDArray[np.float64]: ...
    @property
    def proposals(self) -> int: ...
    @property
    def mean(self) -> npt.NDArray[np.float64]: ...
    @property
    def map_estimate(self) -> npt.NDArray[np.float64]: ...
    @property
    def acceptance_rate(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

class ColorParticleTracker:
    """Colour-histogram particle filter (part-based-graphical-model-pf sections 2-3.2), OpenCV-like."""

    def __init__(
        self,
        *,
        n_particles: int = 30,
        ess_threshold: float = 0.5,
        resampling: str = "systematic",
        seed: int = 0,
        sigma: float = 0.2,
        noise: Tuple[float, float, float, float] = (0.08, 0.03, 0.002, 0.002),
        min_scale: float = 0.8,
        max_scale: float = 1.25,
        min_size: float = 2.0,
        bins_h: int = 16,
        bins_s: int = 4,
        bins_v: int = 4,
        kernel: bool = True,
        template_update: float = 0.0,
        occlusion_threshold: float = 0.75,
        lost_threshold: float = 0.3,
    ) -> None: ...
    def init(self, frame: npt.NDArray[np.uint8], box: Sequence[float]) -> None: ...
    def update(
        self, frame: npt.NDArray[np.uint8]
    ) -> Tuple[bool, Tuple[float, float, float, float]]: ...
    @property
    def box(self) -> Tuple[float, float, float, float]: ...
    @property
    def particles(self) -> npt.NDArray[np.float64]: ...
    @property
    def weights(self) -> npt.NDArray[np.float64]: ...
    @property
    def coefficient(self) -> float: ...
    @property
    def occluded(self) -> bool: ...
    @property
    def initialized(self) -> bool: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

class PartParticleTracker:
    """Part-based particle filter on a graphical model (part-based-graphical-model-pf eqs. 14-30)."""

    def __init__(
        self,
        *,
        edges: Optional[Sequence[Tuple[int, int]]] = None,
        parts: Union[int, Sequence[Sequence[float]]] = 2,
        n_particles: int = 15,
        resampling: str = "multinomial",
        message_weight: str = "neighbour",
        seed: int = 0,
        sigma: float = 0.2,
        noise: Tuple[float, float, float, float] = (0.08, 0.03, 0.002, 0.002),
        min_scale: float = 0.8,
        max_scale: float = 1.25,
        min_size: float = 2.0,
        bins_h: int = 16,
        bins_s: int = 4,
        bins_v: int = 4,
        kernel: bool = True,
        template_update: float = 0.0,
        occlusion_threshold: float = 0.75,
        lost_threshold: float = 0.3,
    ) -> None: ...
    def init(self, frame: npt.NDArray[np.uint8], box: Sequence[float]) -> None: ...
    def update(
        self, frame: npt.NDArray[np.uint8]
    ) -> Tuple[bool, Tuple[float, float, float, float]]: ...
    @property
    def box(self) -> Tuple[float, float, float, float]: ...
    @property
    def parts(self) -> npt.NDArray[np.float64]: ...
    @property
    def occluded(self) -> npt.NDArray[np.bool_]: ...
    @property
    def coefficients(self) -> npt.NDArray[np.float64]: ...
    @property
    def particles(self) -> List[npt.NDArray[np.float64]]: ...
    @property
    def weights(self) -> List[npt.NDArray[np.float64]]: ...
    @property
    def edges(self) -> List[Tuple[int, int]]: ...
    @property
    def initialized(self) -> bool: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @staticmethod
    def default_params() -> Dict[str, Any]: ...

def follow_video(
    video: Union[str, PathLike[str]],
    init_box: Sequence[float],
    method: str,
    first: int,
    last: Optional[int],
    render: Optional[Union[str, PathLike[str]]],
    params: Dict[str, Any],
    progress: Optional[Callable[[int, int], None]],
) -> npt.NDArray[np.float64]: ...

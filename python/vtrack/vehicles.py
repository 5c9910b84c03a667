"""Vehicle dimension estimation from a calibrated road camera (particle-filters-human-vehicle
§3): the road camera (``Camera``, ``read_camera_file``), the §3.1 ray observation of a vehicle's
silhouette (``observe_vehicle``), the §3.2 class mixture prior (``VehicleModelPrior``, Table 1 in
``table1_vehicle_models``, or a models file), the §3.3 samplers and the per-vehicle estimator with
its light/heavy decision (``VehicleDimensionEstimator``), and the run over an observations file
(``estimate_vehicles``, = ``vtrack vehicles --observations``). ``vtrack.synthetic_road`` renders
road scenes with exact ground truth.
"""

from os import PathLike
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _core
from ._core import (
    Camera,
    VehicleDimensionEstimator,
    VehicleModelPrior,
    VehicleObservation,
    observe_vehicle,
    read_camera_file,
    read_vehicle_models_file,
    table1_vehicle_models,
)

CameraLike = Union[Camera, str, PathLike]


def _camera(camera: CameraLike) -> Camera:
    return camera if isinstance(camera, Camera) else read_camera_file(camera)


def _models(models):
    return None if models is None or isinstance(models, (str, PathLike)) else list(models)


def estimate_vehicles(observations: Union[str, PathLike], camera: CameraLike, *,
                      models: Union[None, Sequence[Dict[str, Any]], str, PathLike] = None,
                      out: Optional[Union[str, PathLike]] = None, **params: Any) -> List[Dict[str, Any]]:
    """Estimate every vehicle of an observations file (``vtrack vehicles --observations``).

    observations: a file of lines ``frame,vehicle_id,x,y,w,h`` (an image box) or
    ``frame,vehicle_id,x1,y1,...,xn,yn`` (an image polygon, n >= 3), pixels, frames from 1.
    camera: a :class:`Camera` or a camera file. models: None (Table 1), a list of model dicts or
    a models file. params: :meth:`VehicleDimensionEstimator.default_params` keywords. out: also
    write vehicles.csv (``vehicle_id,class,light_heavy,W,H,L,first_frame,last_frame,
    frames_used``), only when every vehicle is estimated. Returns one dict per vehicle, as
    :meth:`VehicleDimensionEstimator.estimates`.
    """
    return _core._estimate_vehicles_from_file(observations, _camera(camera), _models(models), params, out)


def measure_vehicles(video: Union[str, PathLike], camera: CameraLike, *,
                     models: Union[None, Sequence[Dict[str, Any]], str, PathLike] = None,
                     config: Union[None, str, PathLike, Mapping[str, Any]] = None,
                     out: Optional[Union[str, PathLike]] = None, tracks: Optional[Union[str, PathLike]] = None,
                     render: Optional[Union[str, PathLike]] = None, progress: Any = False,
                     return_tracks: bool = False, **params: Any):
    """Every vehicle of a road video: width, height, length, class, light/heavy (``vtrack vehicles
    VIDEO``): KDE background subtraction, foreground blobs and their outlines, a blob tracker, and
    a :class:`VehicleDimensionEstimator` per vehicle (cpp/include/vtrack/apps/vehicles.hpp).

    camera: a :class:`Camera` or a camera file. models: None (Table 1), model dicts or a models
    file. config: a file or sections ``{"seed", "background", "blobs", "estimator"}``. params: any
    parameter of those sections by name (the estimator's are
    :meth:`VehicleDimensionEstimator.default_params`; blobs: foreground_threshold, blob_closing,
    min_area, min_overlap, merge_min_share, foot_gate, lane_split_gap, lane_split_hold, hidden_horizon,
    hidden_max_passage, hold_views, lost_memory, confirm_frames, min_travel, stitch_gap, max_aspect,
    thin_views; background: ``KdeBackground``'s). out, tracks, render: also write vehicles.csv, the
    MOTChallenge rows of the vehicles' image boxes, the annotated video. progress: True or a
    callable(done, total).

    Returns one dict per vehicle (as :meth:`VehicleDimensionEstimator.estimates`), and with
    return_tracks also the (N, 10) MOTChallenge rows.
    """
    from .pipelines import _config_sections, _reporter
    callback, close = _reporter(progress, "vehicles")
    try:
        vehicles, rows, _ = _core._measure_vehicles(
            video, _camera(camera), _models(models), _config_sections(config), params, render, out, tracks,
            callback)
    finally:
        close()
    return (vehicles, rows) if return_tracks else vehicles


__all__ = [
    "Camera",
    "VehicleDimensionEstimator",
    "VehicleModelPrior",
    "VehicleObservation",
    "estimate_vehicles",
    "measure_vehicles",
    "observe_vehicle",
    "read_camera_file",
    "read_vehicle_models_file",
    "table1_vehicle_models",
]

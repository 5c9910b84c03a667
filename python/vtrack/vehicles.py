"""Vehicle dimension estimation from a calibrated road camera (particle-filters-human-vehicle
§3): the road camera (``Camera``, ``read_camera_file``), the §3.1 ray observation of a vehicle's
silhouette (``observe_vehicle``), and the §3.2 class mixture prior (``VehicleModelPrior``, Table 1
in ``table1_vehicle_models``, or a models file). ``vtrack.synthetic_road`` renders road scenes
with exact ground truth.
"""

from ._core import (
    Camera,
    VehicleModelPrior,
    VehicleObservation,
    observe_vehicle,
    read_camera_file,
    read_vehicle_models_file,
    table1_vehicle_models,
)

__all__ = [
    "Camera",
    "VehicleModelPrior",
    "VehicleObservation",
    "observe_vehicle",
    "read_camera_file",
    "read_vehicle_models_file",
    "table1_vehicle_models",
]

"""Object detectors for the detection-driven trackers: OpenCV's HOG people detector, the RGB
detector of the RGB-D GLMB paper. ``HogPeopleDetector(**params).detect(frame)`` returns an
(N, 5) array of x, y, w, h, score.
"""

from ._core import HogPeopleDetector

__all__ = ["HogPeopleDetector"]

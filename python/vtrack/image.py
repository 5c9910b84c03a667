"""Pixel work (the C++ ``image`` layer): the KDE background model on rgI chromaticity
(mb-tbd paper eqs. 6-10), morphology, foreground masks and integral images.

``KdeBackground(**params).apply(frame)`` turns each H x W x 3 uint8 BGR frame into y, an H x W
float32 image in [0, 1] (near 1 = background), which the multi-Bernoulli tracker consumes.
"""

from ._core import IntegralImage, KdeBackground, bgr_to_rgi, close_square, foreground_mask

__all__ = ["IntegralImage", "KdeBackground", "bgr_to_rgi", "close_square", "foreground_mask"]

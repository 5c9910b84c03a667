"""Pixel work (the C++ ``image`` layer): the KDE background model on rgI chromaticity
(mb-tbd paper eqs. 6-10), morphology, foreground masks and integral images, and the HSV color
histograms, Bhattacharyya coefficients and color likelihood of the part-based paper (§3.1,
eqs. 9-11; ``ColorModel`` scores many boxes against a template in one call).

``KdeBackground(**params).apply(frame)`` turns each H x W x 3 uint8 BGR frame into y, an H x W
float32 image in [0, 1] (near 1 = background), which the multi-Bernoulli tracker consumes.
"""

from ._core import (
    ColorModel,
    IntegralImage,
    KdeBackground,
    bgr_to_rgi,
    bhattacharyya_coefficient,
    bhattacharyya_distance,
    close_square,
    color_log_likelihood,
    foreground_mask,
    hsv_bins,
    hsv_histogram,
)

__all__ = [
    "ColorModel",
    "IntegralImage",
    "KdeBackground",
    "bgr_to_rgi",
    "bhattacharyya_coefficient",
    "bhattacharyya_distance",
    "close_square",
    "color_log_likelihood",
    "foreground_mask",
    "hsv_bins",
    "hsv_histogram",
]

#pragma once
// Colour conversions.
#include <opencv2/core.hpp>

namespace vtrack::image {

// rgI chromaticity (mb-tbd-background-subtraction.txt eqs. 6-8), from an 8-bit BGR frame
// (CV_8UC3, OpenCV's channel order) to CV_32FC3 with channels (r, g, I):
//   r = R / (R + G + B),  g = G / (R + G + B)            (eqs. 6, 7)
//   I = (R + G + B) / (3 * 255)                           (eq. 8, see below)
// Eq. 8 as printed divides the sum by 256, which spans [0, 2.99], while the text says every
// component lies in [0, 1]; we keep the stated range and divide by 3 * 255, the intensity as the
// mean channel value. The bandwidth sigma_I of the background model is in these units.
// The black pixel (R + G + B = 0) has no chromaticity; we define it as the neutral grey point
// r = g = 1/3 (the limit along the grey axis), with I = 0, so no division by zero occurs.
void bgr_to_rgi(const cv::Mat& bgr, cv::Mat& rgi);

}  // namespace vtrack::image

#pragma once
// Connected components of a binary mask with each component's bounding box and area.
#include <opencv2/core.hpp>

namespace vtrack::image {

// The 8-connected components of mask != 0 (CV_8UC1): labels as cv::connectedComponents writes
// them (CV_32S, 0 = background, 1..n-1 = components) and stats as
// cv::connectedComponentsWithStats writes them (n x 5 CV_32S: cv::CC_STAT_LEFT, TOP, WIDTH,
// HEIGHT, AREA), except that the background's row 0 is left zero. Returns n.
// Why not cv::connectedComponentsWithStats: in OpenCV 4.6 its statistics pass costs several
// times the labelling itself on a sparse foreground mask, and runs on OpenCV's thread pool
// whatever the caller's thread setting; the pass here visits the foreground pixels only
// (measured in benchmarks/batch.py's docstring).
int connected_components(const cv::Mat& mask, cv::Mat& labels, cv::Mat& stats);

}  // namespace vtrack::image

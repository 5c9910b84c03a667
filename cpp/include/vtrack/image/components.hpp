#pragma once
// Connected components of a binary mask: each component's bounding box and area.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>  // cv::CC_STAT_*

namespace vtrack::image {

// The 8-connected components of mask != 0 (CV_8UC1), numbered 1..n-1 in the raster order of
// each component's first pixel (0 is the background), with stats as
// cv::connectedComponentsWithStats writes them (n x 5 CV_32S: cv::CC_STAT_LEFT, TOP, WIDTH,
// HEIGHT, AREA), except that the background's row 0 is left zero. Returns n. (OpenCV's own
// numbering follows its 2 x 2 block scan and can differ in order, never in the components.)
// Why not OpenCV's: in OpenCV 4.6 connectedComponentsWithStats' statistics pass costs several
// times the labelling on a sparse foreground mask, and both run on OpenCV's thread pool whatever
// the caller's thread setting (so a one-thread tracker took more than one core: batch.py). This
// labels runs of foreground pixels with a union-find on the calling thread and never writes a
// label image; no caller here needs one.
int connected_components(const cv::Mat& mask, cv::Mat& stats);

}  // namespace vtrack::image

#pragma once
// vtrack.Tracks: filters::Tracks (the estimates of one step) as a Python object.
#include <vector>

#include "common.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/filters/tracks.hpp"

namespace vtrack::bindings {

struct TrackSet {
  filters::Tracks tracks;
};

// (N, 10) float64 MOTChallenge rows frame, id, x, y, w, h, conf, -1, -1, -1.
py::array_t<double> track_rows(const std::vector<apps::TrackRow>& rows);
// (N, 10) float64 MOTChallenge det rows frame, -1, x, y, w, h, conf, -1, -1, -1.
py::array_t<double> detection_rows(const std::vector<apps::Detection>& detections);

}  // namespace vtrack::bindings

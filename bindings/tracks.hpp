#pragma once
// vtrack.Tracks: filters::Tracks (the estimates of one step) as a Python object.
#include <vector>

#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
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

namespace vtrack::bindings {

// The getter of a tracker's `tracks` property: the last step's tracks as vtrack.Tracks.
template <class Tracker>
auto last_tracks() {
  return [](const Tracker& t) {
    ObjectGuard guard(&t);
    return TrackSet{t.tracks()};
  };
}

// The surface of the trackers fed background-subtracted images (MultiBernoulliTracker,
// ReclusteringSirTracker): Tracker(image_size, **params), step(y, frame=None) -> Tracks, tracks,
// image_size, default_params() / params. Tracker has Tracker(width, height, Params),
// step(cv::Mat y, cv::Mat frame) (frame empty: none), tracks(), width(), height() and params().
template <class Tracker, class Params>
void def_foreground_tracker(py::class_<Tracker>& cls) {
  cls.def(py::init([](const py::handle& image_size, const py::kwargs& kwargs) {
           const auto [w, h] = image_size_from(image_size);
           return Tracker(w, h, params_from_kwargs<Params>(kwargs, "tracker"));
         }),
         py::arg("image_size"))
      .def(
          "step",
          [](Tracker& f, const py::handle& y, const py::handle& frame) {
            py::array keep, keep_frame;
            const cv::Mat img = float32_image(y, "y", keep);
            cv::Mat bgr;  // its size: the tracker checks it
            if (!frame.is_none()) bgr = bgr_frame(frame, "frame", keep_frame);
            ObjectGuard guard(&f);
            py::gil_scoped_release release;
            return TrackSet{f.step(img, bgr)};
          },
          py::arg("y"), py::arg("frame") = py::none(),
          "Process one background-subtracted image y (H x W float32 in [0, 1], H and W as "
          "image_size) and, optionally, the BGR frame it came from (H x W x 3 uint8), whose "
          "colours keep the labels on the people when appearance_rate > 0; return the reported "
          "tracks (vtrack.Tracks). Without a frame the labels follow the filter's estimates.")
      .def_property_readonly("tracks", last_tracks<Tracker>(),
                             "The tracks returned by the last step.")
      .def_property_readonly(
          "image_size", [](const Tracker& f) { return py::make_tuple(f.width(), f.height()); });
  def_params<Params>(cls, [](const Tracker& f) { return f.params(); });
}

}  // namespace vtrack::bindings

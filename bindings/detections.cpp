// Bindings of the detection-driven trackers of vtrack::apps: MOTChallenge detection files, the
// box GLMB tracker and OpenCV's HOG people detector.
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl/filesystem.h>

#include "common.hpp"
#include "params.hpp"
#include "vtrack/apps/detection_file.hpp"
#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/track_detections.hpp"

namespace vtrack::bindings {
namespace {

using apps::BoxTrackerParams;
using apps::Detection;
using apps::HogParams;

// MOTChallenge rows (N, >= 6): frame, id, x, y, w, h[, conf, ...], checked like a file's lines
// (ValueError "detections row i: ..." for a non-integer frame and as validate_detection).
std::vector<Detection> detections_from_rows(const py::handle& obj) {
  auto rows = as_matrix(obj, "detections", Nan::Allowed);  // NaN reported per row below
  const auto m = matrix_map(rows);
  if (m.rows() > 0 && (m.cols() < 6 || m.cols() > 10)) {
    throw py::value_error("detections must have 6 to 10 columns (frame, id, x, y, w, h[, conf, "
                          "...]), got " + std::to_string(m.cols()));
  }
  std::vector<Detection> out;
  out.reserve(static_cast<std::size_t>(m.rows()));
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    const std::string where = "detections row " + std::to_string(i) + ": ";
    const double f = m(i, 0);
    if (!(std::isfinite(f) && f == std::floor(f) && std::fabs(f) < 1e15)) {
      throw py::value_error(where + "frame must be an integer, got " + py::repr(py::float_(f)).cast<std::string>());
    }
    Detection d{static_cast<long long>(f), m(i, 2), m(i, 3), m(i, 4), m(i, 5),
                m.cols() > 6 ? m(i, 6) : 1.0};
    apps::validate_detection(d, where);
    out.push_back(d);
  }
  return out;
}

py::array_t<double> detection_rows(const std::vector<Detection>& detections) {
  py::array_t<double> out({static_cast<py::ssize_t>(detections.size()), py::ssize_t{10}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < detections.size(); ++i) {
    const auto& d = detections[i];
    const double values[10] = {static_cast<double>(d.frame), -1, d.x, d.y, d.w, d.h, d.confidence,
                               -1, -1, -1};
    for (int c = 0; c < 10; ++c) o(static_cast<py::ssize_t>(i), c) = values[c];
  }
  return out;
}

py::array_t<double> track_rows(const std::vector<apps::TrackRow>& rows) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{10}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const double values[10] = {static_cast<double>(r.frame), static_cast<double>(r.id), r.x, r.y,
                               r.w, r.h, r.confidence, -1, -1, -1};
    for (int c = 0; c < 10; ++c) o(static_cast<py::ssize_t>(i), c) = values[c];
  }
  return out;
}

// (width, height) as two positive numbers.
std::pair<double, double> image_size_from(const py::handle& obj) {
  if (!py::isinstance<py::sequence>(obj) || py::isinstance<py::str>(obj) ||
      py::len(obj) != 2) {
    throw py::type_error("image_size must be a (width, height) pair, got " +
                         py::repr(obj).cast<std::string>());
  }
  const auto s = py::reinterpret_borrow<py::sequence>(obj);
  const double w = s[0].cast<double>(), h = s[1].cast<double>();
  if (!(w > 0 && h > 0 && std::isfinite(w) && std::isfinite(h))) {
    throw py::value_error("image_size must be positive (width, height), got " +
                          py::repr(obj).cast<std::string>());
  }
  return {w, h};
}

bool is_path(const py::handle& obj) {
  return py::isinstance<py::str>(obj) ||
         py::isinstance(obj, py::module_::import("os").attr("PathLike"));
}

}  // namespace

void bind_detections(py::module_& m) {
  m.def(
      "read_detections",
      [](const std::filesystem::path& path, double min_confidence) {
        std::vector<Detection> d;
        {
          py::gil_scoped_release release;
          d = apps::read_detections(path.string(), min_confidence);
        }
        return detection_rows(d);
      },
      py::arg("path"), py::arg("min_confidence") = -std::numeric_limits<double>::infinity(),
      R"doc(Read a MOTChallenge detection file (frame,id,x,y,w,h[,conf,...], frames from 1) into an
(N, 10) float64 array frame, -1, x, y, w, h, conf, -1, -1, -1 (conf 1 when the file has none),
keeping rows with conf >= min_confidence. Raises vtrack.IoError (an OSError) for a missing file and
vtrack.InvalidArgument (a ValueError) "path:line: ..." for a malformed line, NaN/inf, w or h <= 0
or frame < 1. The same reader as `vtrack track --detections`.)doc");

  m.def(
      "track_detections",
      [](const py::handle& detections, const py::handle& image_size, long long last_frame,
         const py::kwargs& kwargs) {
        BoxTrackerParams params;
        set_from_kwargs(params, kwargs, "tracker");
        std::vector<Detection> dets;
        if (is_path(detections)) {
          const auto path = detections.cast<std::filesystem::path>();
          py::gil_scoped_release release;
          dets = apps::read_detections(path.string());
        } else {
          dets = detections_from_rows(detections);
        }
        const auto [w, h] = image_size.is_none() ? apps::detections_extent(dets)
                                                 : image_size_from(image_size);
        std::vector<apps::TrackRow> rows;
        {
          py::gil_scoped_release release;
          rows = apps::track_detections(dets, w, h, params, last_frame);
        }
        return track_rows(rows);
      },
      py::arg("detections"), py::arg("image_size") = py::none(), py::kw_only(),
      py::arg("last_frame") = 0,
      R"doc(Track the image boxes of MOTChallenge detections with the delta-GLMB filter (box state
[cx, vcx, cy, vcy, w, h]: constant-velocity centre, random-walk size, adaptive birth from the
detections, uniform clutter over the image). The same tracker as `vtrack track --detections DET
--method glmb`: given the same file and parameters, the same rows.

detections: a detection file path, or an (N, 6..10) array of rows frame, id, x, y, w, h[, conf,
...] (frames from 1, id ignored). image_size: (width, height) for the clutter model; default the
extent of the boxes. last_frame: track at least up to this frame. Other keyword arguments are
tracker parameters (see BoxTracker.default_params()). Returns an (K, 10) float64 array of
MOTChallenge rows frame, id, x, y, w, h, 1, -1, -1, -1 for frames 1 .. max(last_frame, last
detection frame), ids 1, 2, ... in order of first appearance. Deterministic.)doc");

  py::class_<apps::BoxTracker>(m, "BoxTracker", R"doc(
Frame-by-frame GLMB tracker of image boxes (the tracker of track_detections): construct with
image_size=(width, height) and keyword parameters (see BoxTracker.default_params()); step() takes
one frame's detections and returns its tracks. Deterministic; step() releases the GIL.
)doc")
      .def(py::init([](const py::handle& image_size, const py::kwargs& kwargs) {
             BoxTrackerParams params;
             set_from_kwargs(params, kwargs, "tracker");
             const auto [w, h] = image_size_from(image_size);
             return apps::BoxTracker(w, h, params);
           }),
           py::arg("image_size"))
      .def(
          "step",
          [](apps::BoxTracker& t, const py::handle& boxes) {
            auto a = as_matrix(boxes, "boxes", Nan::Allowed);
            const auto b = matrix_map(a);
            if (b.rows() > 0 && b.cols() != 4 && b.cols() != 5) {
              throw py::value_error("boxes must have shape (M, 4) or (M, 5) [x, y, w, h(, score)], got (" +
                                    std::to_string(b.rows()) + ", " + std::to_string(b.cols()) + ")");
            }
            std::vector<Detection> dets;
            for (Eigen::Index i = 0; i < b.rows(); ++i) {
              Detection d{1, b(i, 0), b(i, 1), b(i, 2), b(i, 3), b.cols() == 5 ? b(i, 4) : 1.0};
              apps::validate_detection(d, "boxes row " + std::to_string(i) + ": ");
              dets.push_back(d);
            }
            std::vector<apps::BoxTrack> tracks;
            {
              py::gil_scoped_release release;
              tracks = t.step(dets);
            }
            py::array_t<double> out({static_cast<py::ssize_t>(tracks.size()), py::ssize_t{5}});
            auto o = out.mutable_unchecked<2>();
            for (std::size_t i = 0; i < tracks.size(); ++i) {
              const auto& k = tracks[i];
              const double v[5] = {static_cast<double>(k.id), k.x, k.y, k.w, k.h};
              for (int c = 0; c < 5; ++c) o(static_cast<py::ssize_t>(i), c) = v[c];
            }
            return out;
          },
          py::arg("boxes"),
          "One frame: boxes (M, 4) [x, y, w, h] or (M, 5) with a score (M may be 0). Returns the "
          "tracks at this frame, a (T, 5) float64 array [id, x, y, w, h], ids 1, 2, ... in order of "
          "first appearance.")
      .def_property_readonly("frame", [](const apps::BoxTracker& t) { return t.filter().time(); },
                             "Number of frames processed.")
      .def_static(
          "default_params", []() { return params_dict(BoxTrackerParams{}); },
          "The default keyword parameters, as a dict (apps/track_detections.hpp documents them).");

  py::class_<apps::HogPeopleDetector>(m, "HogPeopleDetector", R"doc(
OpenCV's HOG people detector (Dalal & Triggs, the default 64x128 people SVM), the RGB detector of
rgbd-glmb-switching-observation. Keyword parameters: hit_threshold (SVM margin of a hit, 0),
win_stride (px, multiple of 8, 8), padding (px, multiple of 8, 8), scale (pyramid step, 1.1),
upscale (resize before detecting, so people under ~96 px tall are found; 1.5, 1 = off),
group_threshold (overlapping hits a detection needs, 2), min_score (drop grouped detections
scoring less, 0), person_fraction (returned box relative to the 64x128 window, 0.75: the person
inside it). apps/hog_detector.hpp says why these defaults.
)doc")
      .def(py::init([](const py::kwargs& kwargs) {
        HogParams params;
        set_from_kwargs(params, kwargs, "detector");
        return apps::HogPeopleDetector(params);
      }))
      .def(
          "detect",
          [](const apps::HogPeopleDetector& d, const py::handle& frame) {
            py::array keep;
            const cv::Mat img = bgr_frame(frame, "frame", keep);
            std::vector<apps::ScoredBox> boxes;
            {
              py::gil_scoped_release release;
              boxes = d.detect(img);
            }
            py::array_t<double> out({static_cast<py::ssize_t>(boxes.size()), py::ssize_t{5}});
            auto o = out.mutable_unchecked<2>();
            for (std::size_t i = 0; i < boxes.size(); ++i) {
              const auto& b = boxes[i];
              const double v[5] = {b.x, b.y, b.w, b.h, b.score};
              for (int c = 0; c < 5; ++c) o(static_cast<py::ssize_t>(i), c) = v[c];
            }
            return out;
          },
          py::arg("frame"),
          "People in an H x W x 3 uint8 BGR frame: an (N, 5) float64 array [x, y, w, h, score], "
          "best score first. TypeError/ValueError naming `frame` for another dtype or shape. "
          "Releases the GIL; use one detector per thread.")
      .def_property_readonly(
          "params", [](const apps::HogPeopleDetector& d) { return params_dict(d.params()); },
          "The parameters in use, as a dict of keyword arguments.")
      .def_static(
          "default_params", []() { return params_dict(HogParams{}); },
          "The default keyword parameters, as a dict.");
}

}  // namespace vtrack::bindings

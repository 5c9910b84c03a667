// Bindings of the detection-driven trackers of vtrack::apps: MOTChallenge detection files, the
// box GLMB tracker and OpenCV's HOG people detector.
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl/filesystem.h>

#include "args.hpp"
#include "common.hpp"
#include "guard.hpp"
#include "params.hpp"
#include "tracks.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/core/limits.hpp"

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
    if (!(std::isfinite(f) && f == std::floor(f) && std::fabs(f) <= core::kMaxFrame)) {
      throw py::value_error(where + "frame must be an integer, got " + py::repr(py::float_(f)).cast<std::string>());
    }
    Detection d{static_cast<long long>(f), m(i, 2), m(i, 3), m(i, 4), m(i, 5),
                m.cols() > 6 ? m(i, 6) : 1.0};
    apps::validate_detection(d, where);
    out.push_back(d);
  }
  return out;
}

bool is_path(const py::handle& obj) {
  return py::isinstance<py::str>(obj) ||
         py::isinstance(obj, py::module_::import("os").attr("PathLike"));
}

}  // namespace

namespace {

void bind_detection_files(py::module_& m) {
  m.def(
      "read_detections",
      [](const py::handle& path, const py::handle& min_confidence) {
        const std::string file = path_arg(path, "path");
        const double threshold = real_arg(min_confidence, "min_confidence");
        std::vector<Detection> d;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          d = apps::read_detections(file, threshold);
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
      [](const py::handle& detections, const py::handle& image_size, const py::handle& last,
         const py::dict& params, const py::object& progress) {
        BoxTrackerParams p = params_from_kwargs<BoxTrackerParams>(params, "tracker");
        const long long last_frame = int_arg(last, "last_frame", 0, core::kMaxFrame);
        std::vector<Detection> dets;
        if (is_path(detections)) {
          const std::string path = path_arg(detections, "detections");
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          dets = apps::read_detections(path);
        } else {
          dets = detections_from_rows(detections);
        }
        const auto [w, h] = image_size.is_none() ? std::pair<int, int>{0, 0}
                                                 : image_size_from(image_size);
        const apps::FrameProgress report = progress_callback(progress);
        std::vector<apps::TrackRow> rows;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          rows = apps::track_detections(dets, w, h, p, last_frame, report);
        }
        return track_rows(rows);
      },
      py::arg("detections"), py::arg("image_size"), py::arg("last_frame"), py::arg("params"),
      py::arg("progress"),
      "The compiled half of vtrack.track_detections (use that).");
}

void bind_box_tracker(py::module_& m) {
  py::class_<apps::BoxTracker> box(m, "BoxTracker", R"doc(
Frame-by-frame GLMB tracker of image boxes (the tracker of track_detections): construct with
image_size=(width, height) and keyword parameters (BoxTracker.default_params()); step() takes one
frame's detections and returns its tracks as vtrack.Tracks. Deterministic with the default
Murty ranking; step() releases the GIL (calls on one tracker from several threads are
serialised) and Ctrl-C interrupts a long step.
)doc");
  box.def(py::init([](const py::handle& image_size, const py::kwargs& kwargs) {
           const auto [w, h] = image_size_from(image_size);
           return apps::BoxTracker(w, h, params_from_kwargs<BoxTrackerParams>(kwargs, "tracker"));
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
            ObjectGuard guard(&t);
            PythonInterrupts interrupts;  // a large hypothesis budget makes a step long
            py::gil_scoped_release release;
            return TrackSet{t.step(dets)};
          },
          py::arg("boxes"),
          "One frame: boxes (M, 4) [x, y, w, h] or (M, 5) with a score (M may be 0). Returns the "
          "tracks at this frame (vtrack.Tracks: ids 1, 2, ... in order of first report, scores = "
          "existence probabilities, states [cx, vcx, cy, vcy, w, h]).")
      .def_property_readonly(
          "frame",
          [](const apps::BoxTracker& t) {
            ObjectGuard guard(&t);
            return t.tracker().time();
          },
          "Number of frames processed.")
      .def_property_readonly("image_size", [](const apps::BoxTracker& t) {
        return py::make_tuple(t.width(), t.height());
      })
      .def_property_readonly(
          "learnt",
          [](const apps::BoxTracker& t) {
            py::dict d;
            d["clutter_rate"] = t.clutter().rate();
            d["duplicate_rate"] = t.clutter().duplicate_rate();
            d["duplicate_offset_mean"] = Eigen::VectorXd(t.clutter().offsets().mean());
            d["duplicate_offset_cov"] = Eigen::MatrixXd(t.clutter().offsets().covariance());
            d["detection_probability"] = t.detection_probability();
            d["score_target_mean"] = t.score_model().target_mean();
            d["score_clutter_mean"] = t.score_model().clutter_mean();
            d["score_sd"] = t.score_model().sd();
            d["clutter_size_mean"] = Eigen::VectorXd(t.clutter().sizes().mean());
            d["clutter_size_cov"] = Eigen::MatrixXd(t.clutter().sizes().covariance());
            return d;
          },
          "The online estimates after the last step (BoxTracker.default_params()'s learn_* "
          "options): the clutter rate per frame, p_D, the score model's class means and sd on "
          "the probit scale, and the clutter's (log w, log h) mean and covariance.");
  def_params<BoxTrackerParams>(box, [](const apps::BoxTracker& t) { return t.params(); });
}

void bind_hog_detector(py::module_& m) {
  py::class_<apps::HogPeopleDetector> hog(m, "HogPeopleDetector", R"doc(
OpenCV's HOG people detector (Dalal & Triggs, the default 64x128 people SVM), the RGB detector of
rgbd-glmb-switching-observation. Keyword parameters (HogPeopleDetector.default_params(); why these
defaults: apps/hog_detector.hpp): hit_threshold (SVM margin of a hit), win_stride (px, multiple of
8), padding (px, multiple of 8), scale (pyramid step), upscale (resize before detecting, so people
under ~96 px tall are found; 1 = off), group_threshold (overlapping hits a detection needs),
min_score (drop grouped detections scoring less), person_fraction (returned box relative to the
64x128 window: the person inside it).
)doc");
  hog.def(py::init([](const py::kwargs& kwargs) {
           return apps::HogPeopleDetector(params_from_kwargs<HogParams>(kwargs, "detector"));
         }))
      .def(
          "detect",
          [](const apps::HogPeopleDetector& d, const py::handle& frame) {
            py::array keep;
            const cv::Mat img = bgr_frame(frame, "frame", keep);
            std::vector<apps::ScoredBox> boxes;
            {
              ObjectGuard guard(&d);  // OpenCV's HOG keeps scratch state
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
          "Releases the GIL; calls on one detector from several threads are serialised.");
  def_params<HogParams>(hog, [](const apps::HogPeopleDetector& d) { return d.params(); });
}

}  // namespace

void bind_detections(py::module_& m) {
  bind_detection_files(m);
  bind_box_tracker(m);
  bind_hog_detector(m);
}

}  // namespace vtrack::bindings

// The one estimate type of every multi-object tracker, vtrack.Tracks, and MOTChallenge rows.
#include <cmath>
#include <filesystem>

#include <pybind11/stl/filesystem.h>

#include "args.hpp"
#include "common.hpp"
#include "tracks.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/core/limits.hpp"

namespace vtrack::bindings {
namespace {

// (N, 10) float64 MOTChallenge rows frame, id, x, y, w, h, conf, -1, -1, -1.
py::array_t<double> rows_array(const std::vector<apps::TrackRow>& rows) {
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

py::object states_of(const filters::Tracks& tracks) {
  if (tracks.empty() || tracks.front().state.size() == 0) return py::none();
  const auto d = tracks.front().state.size();
  py::array_t<double> out({static_cast<py::ssize_t>(tracks.size()), static_cast<py::ssize_t>(d)});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    for (Eigen::Index j = 0; j < d; ++j) o(static_cast<py::ssize_t>(i), j) = tracks[i].state[j];
  }
  return std::move(out);
}

py::object covariances_of(const filters::Tracks& tracks) {
  if (tracks.empty() || tracks.front().covariance.size() == 0) return py::none();
  const auto d = tracks.front().covariance.rows();
  py::array_t<double> out({static_cast<py::ssize_t>(tracks.size()), static_cast<py::ssize_t>(d),
                           static_cast<py::ssize_t>(d)});
  auto o = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    for (Eigen::Index r = 0; r < d; ++r) {
      for (Eigen::Index c = 0; c < d; ++c) {
        o(static_cast<py::ssize_t>(i), r, c) = tracks[i].covariance(r, c);
      }
    }
  }
  return std::move(out);
}

}  // namespace

py::array_t<double> track_rows(const std::vector<apps::TrackRow>& rows) { return rows_array(rows); }

py::array_t<double> detection_rows(const std::vector<apps::Detection>& detections) {
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

namespace {

void bind_tracks_class(py::module_& m) {
  py::class_<TrackSet>(m, "Tracks", R"doc(
What every multi-object tracker's step() returns: the tracks reported at one step, in id order.

ids          int64 (N,): identities, stable for a track's life (1, 2, ... in order of first report)
boxes        float64 (N, 4): image boxes x, y, w, h (NaN rows when the tracker's state is not an
             image box, e.g. a GlmbTracker on a user's state space)
scores       float64 (N,): confidence in [0, 1] (the existence probability where the filter has one)
states       float64 (N, d) or None: the filter's state estimates
covariances  float64 (N, d, d) or None: their covariances, where the filter has them
labels       int64 (N, 2) or None: the GLMB label (birth time, birth index) of each track

vtrack.io.mot_rows(frame, tracks) turns them into MOTChallenge rows.
)doc")
      .def_property_readonly("ids",
                             [](const TrackSet& t) {
                               py::array_t<std::int64_t> out(static_cast<py::ssize_t>(t.tracks.size()));
                               for (std::size_t i = 0; i < t.tracks.size(); ++i) {
                                 out.mutable_at(i) = static_cast<std::int64_t>(t.tracks[i].id);
                               }
                               return out;
                             })
      .def_property_readonly("boxes",
                             [](const TrackSet& t) {
                               py::array_t<double> out({static_cast<py::ssize_t>(t.tracks.size()),
                                                        py::ssize_t{4}});
                               auto o = out.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < t.tracks.size(); ++i) {
                                 const auto& k = t.tracks[i];
                                 const auto r = static_cast<py::ssize_t>(i);
                                 o(r, 0) = k.x, o(r, 1) = k.y, o(r, 2) = k.w, o(r, 3) = k.h;
                               }
                               return out;
                             })
      .def_property_readonly("scores",
                             [](const TrackSet& t) {
                               py::array_t<double> out(static_cast<py::ssize_t>(t.tracks.size()));
                               for (std::size_t i = 0; i < t.tracks.size(); ++i) {
                                 out.mutable_at(i) = t.tracks[i].score;
                               }
                               return out;
                             })
      .def_property_readonly("states", [](const TrackSet& t) { return states_of(t.tracks); })
      .def_property_readonly("covariances",
                             [](const TrackSet& t) { return covariances_of(t.tracks); })
      .def_property_readonly("labels",
                             [](const TrackSet& t) -> py::object {
                               if (t.tracks.empty() || t.tracks.front().birth_time < 0) {
                                 return py::none();
                               }
                               py::array_t<std::int64_t> out(
                                   {static_cast<py::ssize_t>(t.tracks.size()), py::ssize_t{2}});
                               auto o = out.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < t.tracks.size(); ++i) {
                                 o(static_cast<py::ssize_t>(i), 0) = t.tracks[i].birth_time;
                                 o(static_cast<py::ssize_t>(i), 1) = t.tracks[i].birth_index;
                               }
                               return std::move(out);
                             })
      .def("__len__", [](const TrackSet& t) { return t.tracks.size(); })
      .def("__repr__", [](const TrackSet& t) {
        std::string ids;
        for (const auto& k : t.tracks) ids += (ids.empty() ? "" : ", ") + std::to_string(k.id);
        return "Tracks(ids=[" + ids + "])";
      });
}

void bind_mot_files(py::module_& m) {
  m.def(
      "mot_rows",
      [](const py::handle& frame_arg, const TrackSet& tracks) {
        // MOTChallenge frames are 1-based.
        const long long frame = int_arg(frame_arg, "frame (1-based)", 1, core::kMaxFrame);
        std::vector<apps::TrackRow> rows;
        apps::append_rows(rows, frame, tracks.tracks);
        return rows_array(rows);
      },
      py::arg("frame"), py::arg("tracks"),
      "MOTChallenge rows (N, 10) frame, id, x, y, w, h, conf, -1, -1, -1 of one step's Tracks "
      "(conf = score). ValueError for frame < 1 or a track without an image box.");

  m.def(
      "write_mot",
      [](const py::handle& path_obj, const py::handle& rows) {
        const std::string path = path_arg(path_obj, "path");
        const py::array any = py::array::ensure(rows);
        auto a = any && any.size() == 0 ? py::array_t<double>(std::vector<py::ssize_t>{0, 10})
                                        : as_matrix(rows, "rows", Nan::Rejected);
        if (a.shape(0) > 0 && (a.shape(1) < 7 || a.shape(1) > 10)) {
          throw py::value_error("rows must have 7 to 10 columns (frame, id, x, y, w, h, conf[, "
                                "...]), got " + std::to_string(a.shape(1)));
        }
        const auto m = matrix_map(a);
        std::vector<apps::TrackRow> out;
        for (Eigen::Index i = 0; i < m.rows(); ++i) {
          if (!m.row(i).allFinite()) throw py::value_error("rows contain NaN or infinite values");
          // Range-checked before the casts below (a double beyond the integer's range is UB).
          if (m(i, 0) < 1 || m(i, 0) != std::floor(m(i, 0)) || m(i, 0) > core::kMaxFrame ||
              m(i, 1) < 0 || m(i, 1) != std::floor(m(i, 1)) || m(i, 1) > 9007199254740992.0) {
            throw py::value_error("rows row " + std::to_string(i) +
                                  ": frame must be an integer in [1, 10^15] and id an integer in "
                                  "[0, 2^53]");
          }
          for (int c = 2; c < 6; ++c) {
            if (std::fabs(m(i, c)) > core::kMaxCoordinate) {
              throw py::value_error("rows row " + std::to_string(i) + ": x, y, w and h must be "
                                    "within +-1e9 pixels, got " + std::to_string(m(i, c)));
            }
          }
          out.push_back({static_cast<long long>(m(i, 0)), static_cast<std::uint64_t>(m(i, 1)),
                         static_cast<float>(m(i, 2)), static_cast<float>(m(i, 3)),
                         static_cast<float>(m(i, 4)), static_cast<float>(m(i, 5)), m(i, 6)});
        }
        py::gil_scoped_release release;
        apps::write_mot(path, out);
      },
      py::arg("path"), py::arg("rows"), R"doc(
Write MOTChallenge track rows (N, 7..10: frame, id, x, y, w, h, conf[, ...]) to `path` as
frame,id,x,y,w,h,conf,-1,-1,-1 -- the one track-file writer, the CLI's -- through a temporary file
renamed when complete (nothing half-written is ever left).
)doc");
}

}  // namespace

void bind_tracks(py::module_& m) {
  bind_tracks_class(m);
  bind_mot_files(m);
}

}  // namespace vtrack::bindings

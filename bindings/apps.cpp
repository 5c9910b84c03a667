// Bindings of vtrack::apps: video input.
#include <filesystem>

#include <optional>

#include <pybind11/stl/filesystem.h>

#include "common.hpp"
#include "params.hpp"
#include "vtrack/apps/parameters.hpp"
#include "vtrack/apps/track_video.hpp"
#include "vtrack/apps/video_source.hpp"

namespace vtrack::bindings {

void bind_apps(py::module_& m) {
  py::class_<apps::VideoInfo>(m, "VideoInfo", "What `probe_video` found.")
      .def_readonly("frame_count", &apps::VideoInfo::frame_count)
      .def_readonly("width", &apps::VideoInfo::width)
      .def_readonly("height", &apps::VideoInfo::height)
      .def_readonly("fps", &apps::VideoInfo::fps, "Frames per second; 0.0 when unknown.")
      .def_readonly("is_image_folder", &apps::VideoInfo::is_image_folder)
      .def("__repr__", [](const apps::VideoInfo& v) {
        return "VideoInfo(frame_count=" + std::to_string(v.frame_count) +
               ", width=" + std::to_string(v.width) + ", height=" + std::to_string(v.height) +
               ", fps=" + std::to_string(v.fps) + ")";
      });

  m.def(
      "probe_video",
      [](const std::filesystem::path& path) {
        py::gil_scoped_release release;
        return apps::probe_video(path.string());
      },
      py::arg("path"),
      "Decode a video file or image folder to the end and report its exact frame count, size "
      "and fps. Raises vtrack.IoError (an OSError) for missing, unreadable or corrupt input.");

  m.def(
      "track_video",
      [](const std::filesystem::path& path, const std::string& method, std::uint64_t seed,
         const std::optional<std::filesystem::path>& render, const std::optional<py::dict>& background,
         const py::kwargs& tracker) {
        if (method != "mb") throw py::value_error("method must be 'mb', got '" + method + "'");
        apps::MbPipelineParams params;
        params.seed = seed;
        if (background) set_from_kwargs(params.background, *background, "background");
        set_from_kwargs(params.tracker, tracker, "tracker");
        std::vector<apps::TrackRow> rows;
        {
          py::gil_scoped_release release;
          rows = apps::track_video_mb(path.string(), params, render ? render->string() : "");
        }
        py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{10}});
        auto o = out.mutable_unchecked<2>();
        for (std::size_t i = 0; i < rows.size(); ++i) {
          const auto& r = rows[i];
          const double values[10] = {static_cast<double>(r.frame), static_cast<double>(r.id), r.x,
                                     r.y, r.w, r.h, r.confidence, -1, -1, -1};
          for (int c = 0; c < 10; ++c) o(static_cast<py::ssize_t>(i), c) = values[c];
        }
        return out;
      },
      py::arg("path"), py::arg("method") = "mb", py::kw_only(), py::arg("seed") = 0,
      py::arg("render") = py::none(), py::arg("background") = py::none(),
      R"doc(Track the people in a video (or image folder) with vtrack's main pipeline: the KDE
background model (mb-tbd paper eqs. 6-10) and the multi-Bernoulli track-before-detect filter
(eqs. 20-24). Returns every frame's tracks as an (N, 10) float64 array of MOTChallenge rows
frame, id, x, y, w, h, conf, -1, -1, -1 (frames from 1, conf = existence probability; write it
with vtrack.mot.write_mot). `background` is a dict of KDE parameters (n_samples, period, sigma_r,
sigma_g, sigma_I, closing, threads); other keyword arguments are tracker parameters (see
MultiBernoulliTracker.default_params()). `render` writes the annotated video (.avi, .mp4, .mkv).
The same seed gives the same tracks.)doc");
}

}  // namespace vtrack::bindings

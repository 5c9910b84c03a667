// Bindings of vtrack::apps: video input.
#include <filesystem>

#include <pybind11/stl/filesystem.h>

#include "common.hpp"
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
}

}  // namespace vtrack::bindings

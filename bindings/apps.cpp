// Bindings of vtrack::apps: video input, configuration files and the video pipelines.
#include <filesystem>
#include <string>
#include <vector>

#include <pybind11/stl/filesystem.h>

#include "args.hpp"
#include "common.hpp"
#include "params.hpp"
#include "tracks.hpp"
#include "vtrack/apps/config.hpp"
#include "vtrack/apps/pipeline.hpp"
#include "vtrack/apps/video_source.hpp"

namespace vtrack::bindings {
namespace {

// The kind of parameter a value of this alternative belongs to (for converting a Python value
// given for it).
std::pair<core::ParameterKind, std::size_t> kind_of(const core::ParameterValue& v) {
  using K = core::ParameterKind;
  if (std::holds_alternative<bool>(v)) return {K::flag, 0};
  if (std::holds_alternative<std::int64_t>(v)) return {K::integer, 0};
  if (std::holds_alternative<std::uint64_t>(v)) return {K::seed, 0};
  if (std::holds_alternative<double>(v)) return {K::real, 0};
  if (const auto* r = std::get_if<std::vector<double>>(&v)) return {K::reals, r->size()};
  return {K::choice, 0};
}

// Sets `name` (a parameter of any of the method's sections, or of `section` when not empty) from
// a Python value: TypeError for an unknown name or a wrong type.
void set_from_python(apps::PipelineParams& params, const std::string& section,
                     const std::string& name, const py::handle& value) {
  std::vector<std::string> names;
  for (const auto& s : apps::pipeline_sections(params)) {
    if (!section.empty() && s.name != section) continue;
    for (const auto& [key, current] : s.values) {
      names.push_back(key);
      if (key != name) continue;
      const auto [kind, size] = kind_of(current);
      apps::set_pipeline_parameter(params, name, parameter_from_python(name, kind, size, value));
      return;
    }
  }
  throw_unknown_keyword(name, section.empty() ? params.method : section, names);
}

// A config given as Python sections {"seed": int, "<section>": {name: value}} (what load_config
// returns), applied to `params`.
void apply_python_config(apps::PipelineParams& params, const py::dict& config) {
  for (const auto& item : config) {
    const std::string section = py::str(item.first).cast<std::string>();
    if (section == "seed") {
      set_from_python(params, "", "seed", item.second);
      continue;
    }
    bool known = false;
    for (const auto& s : apps::pipeline_sections(params)) known = known || s.name == section;
    if (!known) {
      throw py::value_error("config: method " + params.method + " has no section '" + section + "'");
    }
    if (!py::isinstance<py::dict>(item.second)) {
      throw py::type_error("config section '" + section + "' must be a dict");
    }
    for (const auto& entry : item.second.cast<py::dict>()) {
      set_from_python(params, section, py::str(entry.first).cast<std::string>(), entry.second);
    }
  }
}

// The pipeline's parameters from a config (Python sections), keywords and `--set name=value`
// texts, in that order of precedence (lowest first), as `vtrack track` resolves them.
apps::PipelineParams pipeline_params(const std::string& method, const std::string& detector,
                                     const py::dict& config, const py::dict& params,
                                     const std::vector<std::string>& settings) {
  apps::PipelineParams p;
  p.method = method;
  p.detector = detector;
  apps::validate(p);  // the method and detector, before names are looked up in them
  apply_python_config(p, config);
  for (const auto& item : params) {
    set_from_python(p, "", py::str(item.first).cast<std::string>(), item.second);
  }
  for (const auto& setting : settings) {
    const auto [name, value] = core::parse_setting(setting);
    apps::set_pipeline_parameter(p, name, value);
  }
  return p;
}

py::dict config_dict(const apps::Config& config) {
  py::dict d;
  if (config.seed) d["seed"] = py::int_(*config.seed);
  for (const auto& [section, values] : config.sections) {
    py::dict s;
    for (const auto& [name, value] : values) s[name.c_str()] = parameter_to_python(value);
    d[section.c_str()] = s;
  }
  return d;
}

}  // namespace

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
      [](const py::handle& path) {
        const std::string file = path_arg(path, "path");
        PythonInterrupts interrupts;  // decodes every frame
        py::gil_scoped_release release;
        return apps::probe_video(file);
      },
      py::arg("path"),
      "Decode a video file or image folder to the end and report its exact frame count, size "
      "and fps. Raises vtrack.IoError (an OSError) for missing, unreadable or corrupt input.");

  m.def(
      "load_config",
      [](const py::handle& path) {
        const std::string file = path_arg(path, "path");
        apps::Config config;
        {
          py::gil_scoped_release release;
          config = apps::read_config(file);
        }
        return config_dict(config);
      },
      py::arg("path"), R"doc(
Read a YAML or JSON config file, as `vtrack track --config` reads it: a dict with the top-level
"seed" (if present) and one dict per section ({"background": {...}, "tracker": {...}, ...}).
Raises vtrack.IoError (an OSError) for a missing, unreadable or unparsable file (naming the line)
and ValueError for a malformed document.
)doc");

  m.def(
      "pipeline_params",
      [](const std::string& method, const std::string& detector, const py::dict& config,
         const py::dict& params, const std::vector<std::string>& settings) {
        const apps::PipelineParams p = pipeline_params(method, detector, config, params, settings);
        apps::validate(p);
        py::dict out;
        for (const auto& section : apps::pipeline_sections(p)) {
          py::dict values;
          for (const auto& [name, value] : section.values) {
            values[name.c_str()] = parameter_to_python(value);
          }
          out[section.name.c_str()] = values;
        }
        return out;
      },
      py::arg("method"), py::arg("detector"), py::arg("config"), py::arg("params"),
      py::arg("settings"),
      "The compiled half of vtrack.pipelines.pipeline_params (use that): every section's "
      "parameters.");

  m.def(
      "track_video",
      [](const py::handle& video_arg, const py::handle& method, const py::handle& detector,
         const py::dict& config, const py::dict& params, const py::handle& render_arg,
         const py::object& progress) {
        const std::string video = path_arg(video_arg, "video");
        const std::string render = render_arg.is_none() ? "" : path_arg(render_arg, "render");
        const apps::PipelineParams p = pipeline_params(
            str_arg(method, "method"), str_arg(detector, "detector"), config, params, {});
        const apps::FrameProgress report = progress_callback(progress);
        apps::PipelineResult result;
        {
          PythonInterrupts interrupts;
          py::gil_scoped_release release;
          result = apps::track_video(video, p, render, report);
        }
        return py::make_tuple(track_rows(result.tracks), detection_rows(result.detections),
                              result.frames);
      },
      py::arg("video"), py::arg("method"), py::arg("detector"), py::arg("config"),
      py::arg("params"), py::arg("render"), py::arg("progress"),
      "The compiled half of vtrack.track_video (use that): (rows, detections, frames).");
}

}  // namespace vtrack::bindings

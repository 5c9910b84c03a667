// The `vtrack` command-line program: parses arguments and calls the library, nothing more.
// Errors print `vtrack: error: ...` on stderr and exit with status 2 (usage) or 1 (failure).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <filesystem>
#include <new>

#include <unistd.h>

#include "batch_handoff.hpp"
#include "signals.hpp"
#include "vtrack/apps/background_subtraction.hpp"
#include "vtrack/apps/config.hpp"
#include "vtrack/apps/follow.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/output_paths.hpp"
#include "vtrack/apps/pipeline.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/apps/vehicles.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/version.hpp"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// A mistake in the command line itself (exit status 2, like argparse).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Command {
  const char* name;
  const char* summary;
  const char* usage;
  std::function<int(const std::vector<std::string>&)> run;
};

bool wants_help(const std::vector<std::string>& args) {
  for (const auto& a : args) {
    if (a == "-h" || a == "--help") return true;
  }
  return false;
}

int run_info(const std::vector<std::string>& args) {
  if (args.size() != 1) throw UsageError("info takes exactly one VIDEO_OR_IMAGE_FOLDER");
  if (!args[0].empty() && args[0][0] == '-') throw UsageError("unknown option '" + args[0] + "'");
  const vtrack::apps::VideoInfo info = vtrack::apps::probe_video(args[0]);
  std::cout << "path: " << args[0] << "\n"
            << "kind: " << (info.is_image_folder ? "image folder" : "video") << "\n"
            << "frames: " << info.frame_count << "\n"
            << "size: " << info.width << "x" << info.height << "\n";
  if (info.fps > 0) {
    std::cout << "fps: " << info.fps << "\n";
  } else {
    std::cout << "fps: unknown\n";
  }
  return 0;
}

// Strict integer parsing: the whole text must be the number.
int parse_int(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  int value = 0;
  try {
    value = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw UsageError(option + " expects an integer, got '" + text + "'");
  }
  return value;
}

// Progress on stderr every 25 frames: one line rewritten in place on a terminal, otherwise one
// line per update. The line is closed when the job ends, however it ends.
class ProgressLine {
 public:
  explicit ProgressLine(std::string job)
      : job_(std::move(job)), tty_(isatty(fileno(stderr)) != 0),
        start_(std::chrono::steady_clock::now()) {}
  ~ProgressLine() { finish(); }

  std::function<void(long long, long long)> callback() {
    return [this](long long done, long long total) {
      vtrack::cli::check_signals();
      if (done % 25 != 0 && done != total) return;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      std::fprintf(stderr, "%s%s: frame %lld", tty_ ? "\r" : "", job_.c_str(), done);
      if (total > 0) std::fprintf(stderr, "/%lld", total);
      std::fprintf(stderr, " (%.1f frames/s)%s", seconds > 0 ? done / seconds : 0.0,
                   tty_ ? "" : "\n");
      printed_ = true;
    };
  }
  void finish() {
    if (printed_ && tty_) std::fputc('\n', stderr);
    printed_ = false;
  }

 private:
  std::string job_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  bool printed_ = false;
};

// Walks a subcommand's arguments: the one positional argument is the input; every option takes
// a value, handed to `option(name, value)`. Returns the input ("" when absent).
std::string walk_arguments(const std::string& command, const std::vector<std::string>& args,
                           const std::function<void(const std::string&, const std::string&)>& option) {
  std::string input;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.empty() || a[0] != '-') {
      if (!input.empty()) {
        throw UsageError(command + " takes one VIDEO, got '" + input + "' and '" + a + "'");
      }
      input = a;
      continue;
    }
    if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
    option(a, args[++i]);
  }
  return input;
}

// Runs `assemble` on parameters from the command line: a value the library rejects is a usage
// error (exit 2), as a malformed command line is.
template <typename Assemble>
void as_usage(const Assemble& assemble) {
  try {
    assemble();
  } catch (const vtrack::InvalidArgument& e) {
    throw UsageError(e.what());
  }
}

// Outputs checked before any work (apps/output_paths.hpp): one that is an input or another
// output is a usage error (exit 2); a folder that does not exist or is not writable exit 1.
void check_outputs(const std::vector<vtrack::apps::NamedPath>& inputs,
                   const std::vector<vtrack::apps::NamedPath>& outputs) {
  std::vector<vtrack::apps::NamedPath> given;
  for (const auto& o : outputs) {
    if (!o.path.empty()) given.push_back(o);
  }
  as_usage([&] { vtrack::apps::check_outputs(inputs, given); });
}

// Removes the outputs a failed run has already completed, so that it leaves none behind.
struct CompletedOutputs {
  std::vector<std::string> paths;
  bool keep = false;
  ~CompletedOutputs() {
    if (keep) return;
    for (const auto& p : paths) {
      std::error_code ec;
      std::filesystem::remove(p, ec);
    }
  }
};

std::uint64_t parse_seed(const std::string& text) {
  std::uint64_t seed = 0;
  as_usage([&] { seed = vtrack::core::seed_value("--seed", vtrack::core::parse_parameter_text(text)); });
  return seed;
}

int run_bgs(const std::vector<std::string>& args) {
  std::string output, config;
  std::vector<std::string> settings;
  const std::string input = walk_arguments("bgs", args, [&](const std::string& a, const std::string& value) {
    if (a == "--out") {
      output = value;
    } else if (a == "--config") {
      config = value;
    } else if (a == "--set") {
      settings.push_back(value);
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  });
  if (input.empty()) throw UsageError("bgs needs a VIDEO (or image folder)");
  if (output.empty()) throw UsageError("bgs needs --out OUT (a folder, or a .avi/.mp4/.mkv file)");
  check_outputs({{"VIDEO", input}, {"--config", config}},
                {{"--out", output, !vtrack::apps::is_video_output(output)}});
  vtrack::image::KdeBackgroundParams params;
  if (!config.empty()) {
    const auto file = vtrack::apps::read_config(config);
    for (const auto& [section, values] : file.sections) {
      if (section != "background") {
        throw vtrack::InvalidArgument("config file '" + config + "': bgs reads only the section "
                                      "background, got '" + section + "'");
      }
    }
    vtrack::core::set_parameters(params, file.section("background"), "background");
  }
  as_usage([&] {
    for (const auto& setting : settings) {
      const auto [name, value] = vtrack::core::parse_setting(setting);
      vtrack::core::set_parameters(params, {{name, value}}, "background");
    }
    vtrack::image::validate(params);
  });
  ProgressLine progress("bgs");
  const auto result = vtrack::apps::run_background_subtraction(input, output, params,
                                                               progress.callback());
  progress.finish();
  std::cout << "wrote " << result.frames << " y images to " << output
            << (result.video ? " (video)" : " (PNG folder)") << "\n";
  return 0;
}

// The options of `vtrack track`, whichever method.
struct TrackOptions {
  std::string input, output, render, method = "mb", config, detections, detector,
      save_detections, image_size;
  std::vector<std::string> settings;
  std::optional<std::uint64_t> seed;
};

// "WxH" with positive integers.
std::pair<int, int> parse_image_size(const std::string& text) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) throw UsageError("--image-size expects WxH, got '" + text + "'");
  const int w = parse_int("--image-size", text.substr(0, x));
  const int h = parse_int("--image-size", text.substr(x + 1));
  as_usage([&] {
    vtrack::core::require_image_side(w, "--image-size width");
    vtrack::core::require_image_side(h, "--image-size height");
  });
  return {w, h};
}

// Which inputs and options a method takes; usage errors for the others.
void check_track_options(const TrackOptions& o) {
  const bool detections = !o.detections.empty();
  if (o.method == "mb" || o.method == "sir") {
    for (const auto& [flag, value] : {std::pair{"--detections", o.detections},
                                      {"--save-detections", o.save_detections},
                                      {"--image-size", o.image_size}}) {
      if (!value.empty()) throw UsageError(std::string(flag) + " needs --method glmb");
    }
    if (o.input.empty()) throw UsageError("track needs a VIDEO (or image folder)");
    return;
  }
  if (detections && !o.input.empty()) throw UsageError("give either a VIDEO or --detections, not both");
  if (detections) {
    for (const auto& [flag, value] : {std::pair{"--detector", o.detector},
                                      {"--render", o.render},
                                      {"--save-detections", o.save_detections}}) {
      if (!value.empty()) throw UsageError(std::string(flag) + " needs a VIDEO, not --detections");
    }
  } else if (o.input.empty()) {
    throw UsageError("track --method glmb needs a VIDEO or --detections FILE");
  } else if (!o.image_size.empty()) {
    throw UsageError("--image-size applies to --detections (a video has its own size)");
  } else if (o.detector.empty()) {
    // Explicit, so that a detector added later cannot silently change what a command line does.
    throw UsageError("--method glmb on a VIDEO needs --detector hog (what gives the boxes)");
  }
}

// The pipeline's parameters from --config, --seed and --set (in that order of precedence,
// lowest first). Without a detector glmb tracks boxes from a file: only its tracker is checked.
vtrack::apps::PipelineParams track_params(const TrackOptions& o) {
  vtrack::apps::PipelineParams params;
  params.method = o.method;
  params.detector = o.detector;
  const auto validate = [&] {
    if (o.method == "glmb" && o.detector.empty()) {
      vtrack::apps::validate(params.box);  // the boxes come from a file
    } else {
      vtrack::apps::validate(params);
    }
  };
  if (!o.config.empty()) {
    // A value out of range in the file is bad data (exit 1), in --set/--seed a usage error (2).
    vtrack::apps::apply_config(params, vtrack::apps::read_config(o.config));
    if (o.settings.empty() && !o.seed) validate();
  }
  as_usage([&] {
    if (o.seed) vtrack::apps::set_pipeline_parameter(params, "seed", *o.seed);
    for (const auto& setting : o.settings) {
      const auto [name, value] = vtrack::core::parse_setting(setting);
      vtrack::apps::set_pipeline_parameter(params, name, value);
    }
    validate();
  });
  return params;
}

// The options `track` and `params` share: --method, --detector, --config, --seed, --set.
bool parameter_option(TrackOptions& o, const std::string& a, const std::string& value) {
  if (a == "--method") {
    o.method = value;
  } else if (a == "--detector") {
    o.detector = value;
  } else if (a == "--config") {
    o.config = value;
  } else if (a == "--seed") {
    o.seed = parse_seed(value);
  } else if (a == "--set") {
    o.settings.push_back(value);
  } else {
    return false;
  }
  return true;
}

// The library's message for an unknown method ("method must be one of mb, sir, glmb, got 'x'"), as
// Python gives it, as a usage error.
void check_method(const TrackOptions& o) {
  vtrack::apps::PipelineParams params;
  params.method = o.method;
  as_usage([&] { vtrack::apps::pipeline_sections(params); });
}

// A parameter value as JSON.
std::string json_value(const vtrack::core::ParameterValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return "\"" + *s + "\"";
  if (const auto* d = std::get_if<double>(&v)) {
    if (std::isnan(*d)) return "NaN";
    if (std::isinf(*d)) return *d > 0 ? "Infinity" : "-Infinity";
    // The shortest of %.15g..%.17g that reads back as the same double (0.1, not 0.10000000000000001).
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, *d);
      if (std::strtod(text, nullptr) == *d) break;
    }
    return text;
  }
  if (const auto* r = std::get_if<std::vector<double>>(&v)) {
    std::string out = "[";
    for (std::size_t i = 0; i < r->size(); ++i) out += (i ? ", " : "") + json_value((*r)[i]);
    return out + "]";
  }
  return vtrack::core::to_text(v);
}

// Config sections as JSON (what --config reads back).
void print_sections(const std::vector<vtrack::apps::PipelineSection>& sections) {
  std::cout << "{\n";
  for (std::size_t s = 0; s < sections.size(); ++s) {
    std::cout << "  \"" << sections[s].name << "\": {\n";
    const auto& values = sections[s].values;
    for (std::size_t i = 0; i < values.size(); ++i) {
      std::cout << "    \"" << values[i].first << "\": " << json_value(values[i].second)
                << (i + 1 < values.size() ? ",\n" : "\n");
    }
    std::cout << "  }" << (s + 1 < sections.size() ? ",\n" : "\n");
  }
  std::cout << "}\n";
}

struct VehicleOptions;
vtrack::apps::VehiclePipelineParams vehicle_params(const VehicleOptions& o);
void print_vehicle_params(const TrackOptions& o);

// `vtrack params`: the parameters a `vtrack track` (or, with --method vehicles, a `vtrack
// vehicles`) with the same options would run with, as JSON sections.
int run_params(const std::vector<std::string>& args) {
  TrackOptions o;
  const std::string input = walk_arguments("params", args, [&](const std::string& a, const std::string& value) {
    if (!parameter_option(o, a, value)) throw UsageError("unknown option '" + a + "'");
  });
  if (!input.empty()) throw UsageError("params takes no VIDEO, got '" + input + "'");
  if (o.method == "vehicles") {
    if (!o.detector.empty()) throw UsageError("--detector is not an option of vehicles");
    print_vehicle_params(o);
    return 0;
  }
  check_method(o);
  print_sections(vtrack::apps::pipeline_sections(track_params(o)));
  return 0;
}

int run_track(const std::vector<std::string>& args) {
  TrackOptions o;
  o.input = walk_arguments("track", args, [&](const std::string& a, const std::string& value) {
    if (parameter_option(o, a, value)) return;
    if (a == "--out") {
      o.output = value;
    } else if (a == "--render") {
      o.render = value;
    } else if (a == "--detections") {
      o.detections = value;
    } else if (a == "--save-detections") {
      o.save_detections = value;
    } else if (a == "--image-size") {
      o.image_size = value;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  });
  check_method(o);
  if (o.output.empty()) throw UsageError("track needs --out TRACKS (MOTChallenge text)");
  if (!o.render.empty() && !vtrack::apps::is_video_output(o.render)) {
    throw UsageError("--render must name a .avi, .mp4 or .mkv file, got '" + o.render + "'");
  }
  check_track_options(o);
  check_outputs({{"VIDEO", o.input}, {"--detections", o.detections}, {"--config", o.config}},
                {{"--out", o.output}, {"--render", o.render}, {"--save-detections", o.save_detections}});
  const auto params = track_params(o);
  ProgressLine progress("track");
  vtrack::apps::PipelineResult result;
  if (!o.detections.empty()) {
    const auto [width, height] =
        o.image_size.empty() ? std::pair<int, int>{0, 0} : parse_image_size(o.image_size);
    result.tracks = vtrack::apps::track_detections(vtrack::apps::read_detections(o.detections),
                                                   width, height, params.box, 0,
                                                   progress.callback());
  } else {
    result = vtrack::apps::track_video(o.input, params, o.render, progress.callback());
  }
  progress.finish();
  // Written only once everything is tracked, so a failure leaves no tracks file; should one of
  // the last writes fail, the outputs already completed (the render) are removed with it.
  CompletedOutputs completed;
  if (!o.render.empty()) completed.paths.push_back(o.render);
  vtrack::apps::write_mot(o.output, result.tracks);
  completed.paths.push_back(o.output);
  if (!o.save_detections.empty()) {
    vtrack::apps::write_detections(o.save_detections, result.detections);
  }
  completed.keep = true;
  std::cout << "wrote " << result.tracks.size() << " track rows to " << o.output;
  if (!o.render.empty()) std::cout << ", the annotated video to " << o.render;
  if (!o.save_detections.empty()) std::cout << ", the detections to " << o.save_detections;
  std::cout << "\n";
  return 0;
}

// "x,y,w,h" as four numbers.
vtrack::filters::Box parse_box(const std::string& text) {
  const auto value = vtrack::core::parse_parameter_text(text);
  const auto* reals = std::get_if<std::vector<double>>(&value);
  if (!reals || reals->size() != 4) throw UsageError("--init expects x,y,w,h, got '" + text + "'");
  return {(*reals)[0], (*reals)[1], (*reals)[2], (*reals)[3]};
}

int run_follow(const std::vector<std::string>& args) {
  std::string output, render, config, init, first = "1", last = "0", particles;
  vtrack::apps::FollowParams params;
  std::vector<std::string> settings;
  std::optional<std::uint64_t> seed;
  const std::string input = walk_arguments("follow", args, [&](const std::string& a, const std::string& value) {
    if (a == "--out") output = value;
    else if (a == "--render") render = value;
    else if (a == "--config") config = value;
    else if (a == "--init") init = value;
    else if (a == "--first") first = value;
    else if (a == "--last") last = value;
    else if (a == "--method") params.method = value;
    else if (a == "--particles") particles = value;
    else if (a == "--seed") seed = parse_seed(value);
    else if (a == "--set") settings.push_back(value);
    else throw UsageError("unknown option '" + a + "'");
  });
  if (input.empty()) throw UsageError("follow needs a VIDEO");
  if (init.empty()) throw UsageError("follow needs --init x,y,w,h (the object's box on --first)");
  if (output.empty()) throw UsageError("follow needs --out TRACK (frame,x,y,w,h text)");
  if (!render.empty() && !vtrack::apps::is_video_output(render)) {
    throw UsageError("--render must name a .avi, .mp4 or .mkv file, got '" + render + "'");
  }
  const vtrack::filters::Box box = parse_box(init);
  const long long first_frame = parse_int("--first", first);
  const long long last_frame = parse_int("--last", last);
  as_usage([&] { vtrack::apps::validate(params); });  // the method's name
  check_outputs({{"VIDEO", input}, {"--config", config}}, {{"--out", output}, {"--render", render}});
  if (!config.empty()) vtrack::apps::apply_follow_config(params, vtrack::apps::read_config(config));
  as_usage([&] {
    if (!particles.empty()) {
      vtrack::apps::set_follow_parameter(params, "n_particles",
                                         vtrack::core::parse_parameter_text(particles));
    }
    if (seed) vtrack::apps::set_follow_parameter(params, "seed", *seed);
    for (const auto& setting : settings) {
      const auto [name, value] = vtrack::core::parse_setting(setting);
      vtrack::apps::set_follow_parameter(params, name, value);
    }
    vtrack::apps::validate(params);
    if (first_frame < 1) throw vtrack::InvalidArgument("--first must be >= 1, got " + first);
    if (last_frame != 0 && last_frame < first_frame) {
      throw vtrack::InvalidArgument("--last must be >= --first, got " + last);
    }
  });
  ProgressLine progress("follow");
  const auto rows = vtrack::apps::follow_video(input, box, params, first_frame, last_frame, render,
                                               progress.callback());
  progress.finish();
  CompletedOutputs completed;  // a failed write of the track removes the render
  if (!render.empty()) completed.paths.push_back(render);
  vtrack::apps::write_follow(output, rows);
  completed.keep = true;
  std::cout << "wrote " << rows.size() << " frames of the " << params.method << " tracker to "
            << output;
  if (!render.empty()) std::cout << ", the annotated video to " << render;
  std::cout << "\n";
  return 0;
}

// The options of `vtrack vehicles`.
struct VehicleOptions {
  std::string input, camera, output, observations, tracks, render, config, models;
  std::vector<std::string> settings;
  std::optional<std::uint64_t> seed;
};

// The pipeline's parameters from --config (sections background, blobs, estimator; top-level
// seed), --seed and --set (in that order of precedence, lowest first).
vtrack::apps::VehiclePipelineParams vehicle_params(const VehicleOptions& o) {
  vtrack::apps::VehiclePipelineParams params;
  if (!o.config.empty()) {
    vtrack::apps::apply_vehicle_config(params, vtrack::apps::read_config(o.config));
    vtrack::apps::validate(params);  // a value out of range in the file is bad data (exit 1)
  }
  as_usage([&] {
    if (o.seed) params.estimator.seed = *o.seed;
    for (const auto& setting : o.settings) {
      const auto [name, value] = vtrack::core::parse_setting(setting);
      vtrack::apps::set_vehicle_parameter(params, name, value);
    }
    vtrack::apps::validate(params);
  });
  return params;
}

void print_vehicle_params(const TrackOptions& o) {
  VehicleOptions v;
  v.config = o.config;
  v.settings = o.settings;
  v.seed = o.seed;
  print_sections(vtrack::apps::vehicle_sections(vehicle_params(v)));
}

int run_vehicles(const std::vector<std::string>& args) {
  VehicleOptions o;
  o.input = walk_arguments("vehicles", args, [&](const std::string& a, const std::string& value) {
    if (a == "--camera") o.camera = value;
    else if (a == "--out") o.output = value;
    else if (a == "--observations") o.observations = value;
    else if (a == "--tracks") o.tracks = value;
    else if (a == "--render") o.render = value;
    else if (a == "--config") o.config = value;
    else if (a == "--models") o.models = value;
    else if (a == "--seed") o.seed = parse_seed(value);
    else if (a == "--set") o.settings.push_back(value);
    else throw UsageError("unknown option '" + a + "'");
  });
  if (o.camera.empty()) throw UsageError("vehicles needs --camera CAMERA (a JSON or YAML camera file)");
  if (o.output.empty()) throw UsageError("vehicles needs --out VEHICLES (a CSV file)");
  if (o.observations.empty() && o.input.empty()) throw UsageError("vehicles needs a VIDEO or --observations OBS");
  if (!o.observations.empty() && !o.input.empty()) throw UsageError("give either a VIDEO or --observations, not both");
  if (!o.observations.empty()) {
    for (const auto& [flag, value] : {std::pair{"--tracks", o.tracks}, {"--render", o.render}}) {
      if (!value.empty()) throw UsageError(std::string(flag) + " needs a VIDEO, not --observations");
    }
  }
  if (!o.render.empty() && !vtrack::apps::is_video_output(o.render)) {
    throw UsageError("--render must name a .avi, .mp4 or .mkv file, got '" + o.render + "'");
  }
  check_outputs({{"VIDEO", o.input}, {"--observations", o.observations}, {"--camera", o.camera},
                 {"--config", o.config}, {"--models", o.models}},
                {{"--out", o.output}, {"--tracks", o.tracks}, {"--render", o.render}});
  const auto params = vehicle_params(o);
  const auto camera = vtrack::models::read_camera_file(o.camera);
  auto models = o.models.empty() ? std::vector<vtrack::models::VehicleModel>{}
                                 : vtrack::models::read_vehicle_models_file(o.models);
  std::vector<vtrack::filters::VehicleEstimate> estimates;
  std::vector<vtrack::apps::TrackRow> rows;
  if (!o.observations.empty()) {
    vtrack::filters::VehicleDimensionEstimator estimator(camera, std::move(models), params.estimator);
    estimates = vtrack::apps::estimate_vehicles(estimator, vtrack::apps::read_vehicle_observations(o.observations));
  } else {
    ProgressLine progress("vehicles");
    auto result = vtrack::apps::measure_vehicles(o.input, camera, std::move(models), params, o.render,
                                                 progress.callback());
    progress.finish();
    estimates = std::move(result.vehicles);
    rows = std::move(result.tracks);
  }
  // Written only once every vehicle is estimated; should a later write fail, the outputs already
  // completed are removed with it.
  CompletedOutputs completed;
  if (!o.render.empty()) completed.paths.push_back(o.render);
  vtrack::apps::write_vehicles_csv(o.output, estimates);
  completed.paths.push_back(o.output);
  if (!o.tracks.empty()) vtrack::apps::write_mot(o.tracks, rows);
  completed.keep = true;
  int valid = 0, heavy = 0;
  for (const auto& e : estimates) valid += e.valid, heavy += e.valid && e.heavy;
  std::cout << "wrote " << estimates.size() << " vehicles (" << heavy << " heavy, " << valid - heavy
            << " light, " << estimates.size() - static_cast<std::size_t>(valid) << " never fully in view) to "
            << o.output << "\n";
  return 0;
}

// `vtrack batch` is Python (vtrack.batch, on Dask): this execs the interpreter vtrack is
// installed in and returns only when there is none.
int run_batch(const std::vector<std::string>& args) {
  throw UsageError(vtrack::cli::exec_python_batch(args));
}

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"info", "print frame count, frame size and frame rate of a video or image folder",
       "vtrack info VIDEO_OR_IMAGE_FOLDER", run_info},
      {"bgs", "KDE background subtraction (rgI, eq. 10): write the y images (255 = background)",
       "vtrack bgs VIDEO --out OUT [--config FILE] [--set name=value ...]\n\n"
       "  VIDEO            a video file or a folder of images\n"
       "  --out OUT        a .avi/.mkv (Motion-JPEG) or .mp4 file, written under a temporary\n"
       "                   name and renamed when complete; any other name is a folder of PNGs\n"
       "                   000000.png, 000001.png, ... (0-based frame index); if the input is\n"
       "                   corrupt, the images of the frames before the error stay and are valid\n"
       "  --config FILE    YAML or JSON with a section background (the names below)\n"
       "  --set name=value one KDE parameter (repeatable; defaults in brackets):\n"
       "                   n_samples [10], period [10], bandwidth=r,g,I [0.03,0.03,0.06],\n"
       "                   closing [5], threads [0], update_threshold [0.5],\n"
       "                   update_max_skips [3], illumination_compensation [false]",
       run_bgs},
      {"track",
       "track people: KDE background + multi-Bernoulli TBD filter (mb) or re-clustering SIR\n"
       "(sir), or detections + GLMB",
       "vtrack track VIDEO --out TRACKS [--method mb|sir] [--render OUT.mp4] [--config FILE]\n"
       "                    [--seed N] [--set name=value ...]\n"
       "       vtrack track VIDEO --method glmb --detector hog --out TRACKS [--render OUT.mp4]\n"
       "                    [--save-detections DET] [--config FILE] [--seed N]\n"
       "                    [--set name=value ...]\n"
       "       vtrack track --detections DET --method glmb --out TRACKS [--image-size WxH]\n"
       "                    [--config FILE] [--seed N] [--set name=value ...]\n\n"
       "  VIDEO            a video file or a folder of images\n"
       "  --out TRACKS     MOTChallenge text: frame,id,x,y,w,h,conf,-1,-1,-1 (frames from 1,\n"
       "                   conf = the track's score); written only when tracking succeeded\n"
       "  --method mb      the multi-Bernoulli track-before-detect tracker (mb-tbd paper)\n"
       "  --method sir     the multi-person SIR with measurement-guided re-clustering\n"
       "                   (particle-filters-human-vehicle §2) on the KDE's foreground pixels\n"
       "  --method glmb    the delta-GLMB tracker on image boxes (state: box centre, velocity,\n"
       "                   size), from a MOTChallenge det file or from HOG people detections\n"
       "  --detections DET MOTChallenge det rows frame,id,x,y,w,h[,conf,...] (frames from 1)\n"
       "  --image-size WxH image size for the clutter model (default: the extent of the boxes)\n"
       "  --detector hog   OpenCV's HOG people detector on every frame (required with a VIDEO)\n"
       "  --save-detections DET  also write the detector's boxes as MOTChallenge det rows\n"
       "  --render FILE    also write the video with each track's box in its own colour\n"
       "  --config FILE    YAML or JSON: a top-level seed and sections of parameters. mb:\n"
       "                   background (vtrack.KdeBackground.default_params() in Python) and\n"
       "                   tracker (vtrack.MultiBernoulliTracker.default_params()); sir:\n"
       "                   background and tracker (vtrack.ReclusteringSirTracker.default_params());\n"
       "                   glmb:\n"
       "                   detector (vtrack.HogPeopleDetector.default_params()) and tracker\n"
       "                   (vtrack.BoxTracker.default_params())\n"
       "  --seed N         the tracker's seed, 0 to 2^64-1 (default 0): the same seed gives the\n"
       "                   same tracks (glmb uses it only with ranking=gibbs)\n"
       "  --set name=value one parameter of any of the method's sections (repeatable); lists\n"
       "                   as a,b,c",
       run_track},
      {"follow",
       "follow one object from a box: colour or part-based particle filter (OpenCV-tracker-like)",
       "vtrack follow VIDEO --init x,y,w,h --out TRACK [--first N] [--last M]\n"
       "                    [--method color|parts] [--particles N] [--render OUT.mp4]\n"
       "                    [--config FILE] [--seed N] [--set name=value ...]\n\n"
       "  VIDEO            a video file or a folder of images\n"
       "  --init x,y,w,h   the object's box on frame --first (inside the image)\n"
       "  --first N        the frame of the init box, from 1 in the video's numbering (default 1)\n"
       "  --last M         the last frame to follow (default: the end)\n"
       "  --out TRACK      text, frame,x,y,w,h per line from --first on (x,y,w,h = nan where the\n"
       "                   target is lost); written only when following succeeded\n"
       "  --method color   the colour-histogram particle filter (default; N = 30)\n"
       "  --method parts   the part-based particle filter on a graphical model (2 parts, N = 15\n"
       "                   per part; --set parts=3 for a face)\n"
       "  --particles N    particles (per part for parts)\n"
       "  --render FILE    also write the video with the box (parts: each part, red if occluded)\n"
       "  --config FILE    YAML or JSON with a section tracker (vtrack.ColorParticleTracker or\n"
       "                   vtrack.PartParticleTracker.default_params()) and a top-level seed\n"
       "  --seed N         0 to 2^64-1 (default 0): the same seed gives the same track\n"
       "  --set name=value one parameter of the tracker (repeatable)",
       run_follow},
      {"params", "print the parameters a track run would use, as JSON config sections",
       "vtrack params [--method mb|sir|glmb|vehicles] [--detector hog] [--config FILE] [--seed N]\n"
       "              [--set name=value ...]\n\n"
       "  Resolves the defaults, the config file, --seed and --set exactly as `vtrack track`\n"
       "  (`vtrack vehicles` for --method vehicles) does and prints the result: each section\n"
       "  of the method with every parameter.",
       run_params},
      {"vehicles",
       "vehicle dimensions (W, H, L), class and light/heavy from a calibrated road camera",
       "vtrack vehicles VIDEO --camera CAMERA --out VEHICLES [--tracks TRACKS]\n"
       "                [--render OUT.mp4] [--models FILE] [--config FILE] [--seed N]\n"
       "                [--set name=value ...]\n"
       "       vtrack vehicles --observations OBS --camera CAMERA --out VEHICLES [--models FILE]\n"
       "                [--config FILE] [--seed N] [--set name=value ...]\n\n"
       "  VIDEO            a video file or a folder of images: KDE background subtraction,\n"
       "                   foreground blobs and their outlines, a blob tracker, the estimator\n"
       "  --tracks TRACKS  also write MOTChallenge rows frame,id,x,y,w,h,1,-1,-1,-1 of every\n"
       "                   vehicle's image box per frame (ids = vehicle_id)\n"
       "  --render FILE    also write the video with each vehicle's outline, id and class\n"
       "  --observations OBS  silhouettes per line: frame,vehicle_id,x,y,w,h (an image box) or\n"
       "                   frame,vehicle_id,x1,y1,...,xn,yn (a polygon, n >= 3); pixels, frames\n"
       "                   from 1; '#' comments and a header line 'frame,...' skipped\n"
       "  --camera CAMERA  JSON or YAML: K (3x3), dist, R (3x3), t (3), x_cam = R X + t, world\n"
       "                   in metres, Z up, road Z = 0; optional road_axis_world, image_size\n"
       "  --out VEHICLES   CSV vehicle_id,class,light_heavy,W,H,L,first_frame,last_frame,\n"
       "                   frames_used (metres); written only when every vehicle is estimated; a\n"
       "                   vehicle never fully in view: class not_fully_in_view, light_heavy unknown\n"
       "  --models FILE    vehicle classes (YAML/JSON list `models` of {name, W, H, L, sigma_w,\n"
       "                   sigma_h, sigma_l, weight, heavy}); default the paper's Table 1\n"
       "  --config FILE    YAML or JSON: a top-level seed and sections estimator\n"
       "                   (vtrack.vehicles.VehicleDimensionEstimator.default_params()), blobs\n"
       "                   (below) and background (vtrack.KdeBackground.default_params())\n"
       "  --seed N         the samplers' seed (default 0): the same seed, the same answer\n"
       "  --set name=value one estimator parameter (repeatable): sampler [rays] (ray, mh,\n"
       "                   discrete), reference [map] (mean, random, all), n_particles [100],\n"
       "                   burn_in [50], thinning [1], proposal_scale [0.2], dynamic_sigma [0.3],\n"
       "                   min_size [0.4,0.6,1.0], sigma_w/sigma_h/sigma_l [0.25], max_edge_px [4],\n"
       "                   light_heavy_rule [volume] (class), heavy_volume [45], decision [auto]\n"
       "                   (mean, last), border_margin_px [1]; blobs: foreground_threshold [0.5],\n"
       "                   blob_closing [0: 5 px at focal length 900 px, scaled by f/900; 1 off],\n"
       "                   min_area [0: 150 px at f = 900, scaled by (f/900)^2], min_overlap [0.2],\n"
       "                   lost_memory [5], confirm_frames [3]; and the background's",
       run_vehicles},
      {"batch", "track many videos at once on Dask, locally or on a cluster (vtrack.batch)",
       "vtrack batch INPUTS... --out DIR [options]   (vtrack batch --help lists them)", run_batch},
  };
  return table;
}

void print_help() {
  std::cout << "usage: vtrack [--help] [--version] COMMAND [ARGS]\n\n"
               "Bayesian visual multi-object tracking.\n\ncommands:\n";
  for (const auto& c : commands()) {
    std::cout << "  " << c.name << std::string(10 - std::string(c.name).size(), ' ') << c.summary
              << "\n";
  }
  std::cout << "\nRun 'vtrack COMMAND --help' for a command's options.\n";
}

}  // namespace

int main(int argc, char** argv) {
  vtrack::apps::quiet_video_backend_logs();  // our error messages say what went wrong
  vtrack::cli::install_signal_handlers();
  const vtrack::core::InterruptScope interrupts(vtrack::cli::check_signals);
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty()) throw UsageError("no command given (try 'vtrack --help')");
    const std::string first = args.front();
    if (first == "-h" || first == "--help") {
      print_help();
      return 0;
    }
    if (first == "--version") {
      std::cout << "vtrack " << vtrack::kVersion << "\n";
      return 0;
    }
    for (const auto& command : commands()) {
      if (first != command.name) continue;
      std::vector<std::string> rest(args.begin() + 1, args.end());
      if (wants_help(rest) && std::string(command.name) != "batch") {  // batch: Python's help
        std::cout << "usage: " << command.usage << "\n\n" << command.summary << "\n";
        return 0;
      }
      return command.run(rest);
    }
    throw UsageError("unknown command '" + first + "' (try 'vtrack --help')");
  } catch (const UsageError& e) {
    std::cerr << "vtrack: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const vtrack::cli::Interrupted& e) {
    std::cerr << "\nvtrack: interrupted\n";
    return 128 + e.signal;
  } catch (const std::bad_alloc&) {
    std::cerr << "vtrack: error: out of memory (a size, count or budget is larger than this "
                 "machine's memory allows)\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "vtrack: error: " << e.what() << "\n";
    return kExitFailure;
  }
}

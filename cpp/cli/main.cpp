// The `vtrack` command-line program: parses arguments and calls the library, nothing more.
// Errors print `vtrack: error: ...` on stderr and exit with status 2 (usage) or 1 (failure).
#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <unistd.h>

#include "batch_handoff.hpp"
#include "vtrack/apps/background_subtraction.hpp"
#include "vtrack/apps/detection_file.hpp"
#include "vtrack/apps/parameters.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/apps/track_video.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/errors.hpp"
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

// Strict number parsing: the whole text must be the number.
template <typename Number>
Number parse_number(const std::string& option, const std::string& text, const char* what) {
  std::size_t used = 0;
  Number value{};
  try {
    if constexpr (std::is_integral_v<Number>) {
      value = std::stoi(text, &used);
    } else {
      value = std::stod(text, &used);
    }
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw UsageError(option + " expects " + what + ", got '" + text + "'");
  }
  return value;
}

int parse_int(const std::string& option, const std::string& text) {
  return parse_number<int>(option, text, "an integer");
}

double parse_double(const std::string& option, const std::string& text) {
  return parse_number<double>(option, text, "a number");
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

int run_bgs(const std::vector<std::string>& args) {
  std::string output;
  vtrack::image::KdeBackgroundParams params;
  const std::string input = walk_arguments("bgs", args, [&](const std::string& a, const std::string& value) {
    if (a == "--out") {
      output = value;
    } else if (a == "--samples") {
      params.n_samples = parse_int(a, value);
    } else if (a == "--period") {
      params.period = parse_int(a, value);
    } else if (a == "--closing") {
      params.closing = parse_int(a, value);
    } else if (a == "--threads") {
      params.threads = parse_int(a, value);
    } else if (a == "--bandwidth") {
      std::vector<double> sigmas;
      std::size_t start = 0;
      while (true) {
        const std::size_t comma = value.find(',', start);
        sigmas.push_back(parse_double(a, value.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      if (sigmas.size() != 3) {
        throw UsageError("--bandwidth expects three numbers r,g,I, got '" + value + "'");
      }
      params.sigma_r = sigmas[0];
      params.sigma_g = sigmas[1];
      params.sigma_I = sigmas[2];
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  });
  if (input.empty()) throw UsageError("bgs needs a VIDEO (or image folder)");
  if (output.empty()) throw UsageError("bgs needs --out OUT (a folder, or a .avi/.mp4/.mkv file)");
  try {
    vtrack::image::validate(params);
  } catch (const vtrack::InvalidArgument& e) {
    throw UsageError(e.what());
  }

  ProgressLine progress("bgs");
  vtrack::apps::BgsResult result;
  result = vtrack::apps::run_background_subtraction(input, output, params, progress.callback());
  progress.finish();
  std::cout << "wrote " << result.frames << " y images to " << output
            << (result.video ? " (video)" : " (PNG folder)") << "\n";
  return 0;
}

// `--set name=value`: a number, true/false, or a name (e.g. resampling=residual).
vtrack::apps::ParameterValue parse_value(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  std::size_t used = 0;
  try {
    const long long i = std::stoll(text, &used);
    if (used == text.size()) return i;
    const double d = std::stod(text, &used);
    if (used == text.size()) return d;
  } catch (const std::exception&) {
  }
  return text;
}

// The options of `vtrack track`, whichever method.
struct TrackOptions {
  std::string input, output, render, method = "mb", config, detections, detector,
      save_detections, image_size;
  std::vector<std::string> settings;
  long long seed = -1;
};

// Applies each `--set name=value` with the first setter that knows the name.
void apply_settings(
    const std::vector<std::string>& settings,
    const std::vector<std::function<bool(const std::string&, const vtrack::apps::ParameterValue&)>>&
        setters) {
  for (const auto& setting : settings) {
    const std::size_t eq = setting.find('=');
    if (eq == std::string::npos) throw UsageError("--set expects name=value, got '" + setting + "'");
    const std::string name = setting.substr(0, eq);
    const auto value = parse_value(setting.substr(eq + 1));
    bool known = false;
    for (const auto& set : setters) {
      if ((known = set(name, value))) break;
    }
    if (!known) throw UsageError("--set: unknown parameter '" + name + "'");
  }
}

template <typename Params>
std::function<bool(const std::string&, const vtrack::apps::ParameterValue&)> setter(Params& p) {
  return [&p](const std::string& name, const vtrack::apps::ParameterValue& value) {
    return vtrack::apps::set_parameter(p, name, value);
  };
}

// Runs `validate` on parameters assembled from the command line: a bad value is a usage error.
template <typename Validate>
void validate_usage(const Validate& validate) {
  try {
    validate();
  } catch (const vtrack::InvalidArgument& e) {
    throw UsageError(e.what());
  }
}

int run_track_mb(const TrackOptions& o) {
  for (const auto& [flag, value] : {std::pair{"--detections", o.detections},
                                    {"--detector", o.detector},
                                    {"--save-detections", o.save_detections},
                                    {"--image-size", o.image_size}}) {
    if (!value.empty()) throw UsageError(std::string(flag) + " needs --method glmb");
  }
  if (o.input.empty()) throw UsageError("track needs a VIDEO (or image folder)");
  vtrack::apps::MbPipelineParams params;
  if (!o.config.empty()) vtrack::apps::load_pipeline_config(o.config, params);
  if (o.seed >= 0) params.seed = static_cast<std::uint64_t>(o.seed);
  apply_settings(o.settings, {setter(params.background), setter(params.tracker)});
  validate_usage([&] {
    vtrack::image::validate(params.background);
    vtrack::filters::validate(params.tracker);
  });
  ProgressLine progress("track");
  const auto rows = vtrack::apps::track_video_mb(o.input, params, o.render, progress.callback());
  progress.finish();
  // Written only once the whole video is tracked, so a failure leaves no tracks file.
  vtrack::apps::write_mot(o.output, rows);
  std::cout << "wrote " << rows.size() << " track rows to " << o.output;
  if (!o.render.empty()) std::cout << " and the annotated video to " << o.render;
  std::cout << "\n";
  return 0;
}

// "WxH" with positive integers.
std::pair<double, double> parse_image_size(const std::string& text) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) throw UsageError("--image-size expects WxH, got '" + text + "'");
  const int w = parse_int("--image-size", text.substr(0, x));
  const int h = parse_int("--image-size", text.substr(x + 1));
  if (w <= 0 || h <= 0) throw UsageError("--image-size must be positive, got '" + text + "'");
  return {w, h};
}

int run_track_glmb(const TrackOptions& o) {
  if (!o.detections.empty()) {
    if (!o.input.empty()) throw UsageError("give either a VIDEO or --detections, not both");
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
  if (!o.detector.empty() && o.detector != "hog") {
    throw UsageError("--detector must be 'hog' (got '" + o.detector + "')");
  }
  vtrack::apps::GlmbPipelineParams params;
  if (!o.config.empty()) vtrack::apps::load_pipeline_config(o.config, params);
  // The seed matters only with gibbs_ranking (Murty's ranking is deterministic).
  if (o.seed >= 0) params.tracker.seed = static_cast<int>(o.seed);
  apply_settings(o.settings, {setter(params.detector), setter(params.tracker)});
  validate_usage([&] {
    vtrack::apps::validate(params.detector);
    vtrack::apps::validate(params.tracker);
  });
  ProgressLine progress("track");
  std::vector<vtrack::apps::TrackRow> rows;
  if (!o.detections.empty()) {
    const auto size = o.image_size.empty() ? std::pair<double, double>{} : parse_image_size(o.image_size);
    const auto detections = vtrack::apps::read_detections(o.detections);
    const auto [width, height] =
        o.image_size.empty() ? vtrack::apps::detections_extent(detections) : size;
    rows = vtrack::apps::track_detections(detections, width, height, params.tracker, 0,
                                          progress.callback());
  } else {
    auto result = vtrack::apps::track_video_glmb(o.input, params.detector, params.tracker,
                                                 o.render, progress.callback());
    rows = std::move(result.tracks);
    if (!o.save_detections.empty()) {
      vtrack::apps::write_detections(o.save_detections, result.detections);
    }
  }
  progress.finish();
  // Written only once everything is tracked, so a failure leaves no tracks file.
  vtrack::apps::write_mot(o.output, rows);
  std::cout << "wrote " << rows.size() << " track rows to " << o.output;
  if (!o.render.empty()) std::cout << ", the annotated video to " << o.render;
  if (!o.save_detections.empty()) std::cout << ", the detections to " << o.save_detections;
  std::cout << "\n";
  return 0;
}

int run_track(const std::vector<std::string>& args) {
  TrackOptions o;
  o.input = walk_arguments("track", args, [&](const std::string& a, const std::string& value) {
    if (a == "--out") {
      o.output = value;
    } else if (a == "--method") {
      o.method = value;
    } else if (a == "--render") {
      o.render = value;
    } else if (a == "--config") {
      o.config = value;
    } else if (a == "--seed") {
      o.seed = parse_int(a, value);
      if (o.seed < 0) throw UsageError("--seed must be >= 0, got " + value);
    } else if (a == "--set") {
      o.settings.push_back(value);
    } else if (a == "--detections") {
      o.detections = value;
    } else if (a == "--detector") {
      o.detector = value;
    } else if (a == "--save-detections") {
      o.save_detections = value;
    } else if (a == "--image-size") {
      o.image_size = value;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  });
  if (o.method != "mb" && o.method != "glmb") {
    throw UsageError("--method must be 'mb' or 'glmb' (got '" + o.method + "')");
  }
  if (o.output.empty()) throw UsageError("track needs --out TRACKS (MOTChallenge text)");
  if (!o.render.empty() && !vtrack::apps::is_video_output(o.render)) {
    throw UsageError("--render must name a .avi, .mp4 or .mkv file, got '" + o.render + "'");
  }
  return o.method == "mb" ? run_track_mb(o) : run_track_glmb(o);
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
       "vtrack bgs VIDEO --out OUT [--samples N] [--period K] [--bandwidth r,g,I] [--closing K]\n"
       "                  [--threads T]\n\n"
       "  VIDEO            a video file or a folder of images\n"
       "  --out OUT        a .avi/.mkv (Motion-JPEG) or .mp4 file, written under a temporary\n"
       "                   name and renamed when complete; any other name is a folder of PNGs\n"
       "                   000000.png, 000001.png, ... (0-based frame index); if the input is\n"
       "                   corrupt, the images of the frames before the error stay and are valid\n"
       "  --samples N      N0, samples in the background stack (default 10)\n"
       "  --period K       K0, frames between samples (default 10)\n"
       "  --bandwidth r,g,I  kernel bandwidths sigma_r,sigma_g,sigma_I (default 0.03,0.03,0.06)\n"
       "  --closing K      side of the square closing y, 0 = off (default 3)\n"
       "  --threads T      0 = OpenCV default, 1 = single thread (default 0)",
       run_bgs},
      {"track",
       "track people: KDE background + multi-Bernoulli TBD filter (mb), or detections + GLMB",
       "vtrack track VIDEO --out TRACKS [--method mb] [--render OUT.mp4] [--config FILE]\n"
       "                    [--seed N] [--set name=value ...]\n"
       "       vtrack track VIDEO --method glmb --detector hog --out TRACKS [--render OUT.mp4]\n"
       "                    [--save-detections DET] [--config FILE] [--seed N]\n"
       "                    [--set name=value ...]\n"
       "       vtrack track --detections DET --method glmb --out TRACKS [--image-size WxH]\n"
       "                    [--config FILE] [--seed N] [--set name=value ...]\n\n"
       "  VIDEO            a video file or a folder of images\n"
       "  --out TRACKS     MOTChallenge text: frame,id,x,y,w,h,conf,-1,-1,-1 (frames from 1,\n"
       "                   conf = existence probability); written only when tracking succeeded\n"
       "  --method mb      the multi-Bernoulli track-before-detect tracker (mb-tbd paper)\n"
       "  --method glmb    the delta-GLMB tracker on image boxes (state: box centre, velocity,\n"
       "                   size), from a MOTChallenge det file or from HOG people detections\n"
       "  --detections DET MOTChallenge det rows frame,id,x,y,w,h[,conf,...] (frames from 1)\n"
       "  --image-size WxH image size for the clutter model (default: the extent of the boxes)\n"
       "  --detector hog   OpenCV's HOG people detector on every frame (required with a VIDEO)\n"
       "  --save-detections DET  also write the detector's boxes as MOTChallenge det rows\n"
       "  --render FILE    also write the video with each track's box in its own colour\n"
       "  --config FILE    YAML or JSON. mb: sections seed, background (n_samples, period,\n"
       "                   sigma_r, sigma_g, sigma_I, closing, threads) and tracker (delta_f,\n"
       "                   delta_b, closing_size, sigma_x, ..., see vtrack.MultiBernoulliTracker\n"
       "                   .default_params() in Python); glmb: sections detector (hit_threshold,\n"
       "                   win_stride, padding, scale, upscale, group_threshold, min_score,\n"
       "                   person_fraction) and\n"
       "                   tracker (detection_probability, clutter_rate, sigma_accel, ...; see\n"
       "                   vtrack.BoxTracker.default_params() in Python)\n"
       "  --seed N         random seed (default 0): the same seed gives the same tracks (mb; glmb\n"
       "                   with gibbs_ranking -- Murty's ranking is deterministic)\n"
       "  --set name=value override one parameter of a config section (repeatable)",
       run_track},
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
  } catch (const std::exception& e) {
    std::cerr << "vtrack: error: " << e.what() << "\n";
    return kExitFailure;
  }
}

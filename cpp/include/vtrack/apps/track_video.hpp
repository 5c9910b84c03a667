#pragma once
// vtrack's main job: video -> KDE background model (mb-tbd paper Section 3.1) -> multi-Bernoulli
// track-before-detect filter (Sections 3.2-4) -> labelled tracks, in MOTChallenge rows, with an
// optional annotated video.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vtrack/filters/multi_bernoulli.hpp"
#include "vtrack/image/kde_background.hpp"

namespace vtrack::apps {

struct MbPipelineParams {
  image::KdeBackgroundParams background;
  filters::MultiBernoulliParams tracker;
  std::uint64_t seed = 0;
};

// One MOTChallenge row: frame (1-based), id, box (left, top, width, height), confidence.
struct TrackRow {
  long long frame = 0;
  std::uint64_t id = 0;
  float x = 0, y = 0, w = 0, h = 0;
  double confidence = 0.0;
};

// Called after every frame with (frames done, frames announced by the input or -1 if unknown).
using FrameProgress = std::function<void(long long done, long long total)>;

// Reads parameters from a YAML or JSON file (OpenCV's FileStorage reads both):
//   seed: 7
//   background: {n_samples: 10, period: 10, sigma_r: 0.03, ...}   (KdeBackgroundParams names)
//   tracker: {delta_f: 0.1, max_particles: 400, ...}                (MultiBernoulliParams names)
// into `params` (unlisted parameters keep their values). IoError for a missing or unparsable
// file, InvalidArgument naming an unknown section, an unknown parameter or a value of the wrong
// kind.
void load_pipeline_config(const std::string& path, MbPipelineParams& params);

// Runs the pipeline over every frame of `input` (a video file or image folder) and returns the
// tracks of every frame, confidence = existence probability. When `render` is not empty, writes
// the frames with each track's box in a colour of its own (AtomicVideoWriter: nothing is left
// behind on error). IoError naming the frame for corrupt or truncated input.
std::vector<TrackRow> track_video_mb(const std::string& input, const MbPipelineParams& params,
                                     const std::string& render = {},
                                     const FrameProgress& progress = {});

// Writes rows as MOTChallenge text (frame,id,x,y,w,h,conf,-1,-1,-1) to a temporary file renamed
// to `path` when complete.
void write_mot(const std::string& path, const std::vector<TrackRow>& rows);

// Draws a box and its label onto `frame` in a colour derived from the label.
void draw_labelled_box(cv::Mat& frame, std::uint64_t label, double x, double y, double w,
                       double h);

// Draws each track's box and label onto `frame` in a colour derived from the label.
void draw_tracks(cv::Mat& frame, const std::vector<filters::Track>& tracks);

}  // namespace vtrack::apps

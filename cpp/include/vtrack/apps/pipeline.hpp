#pragma once
// vtrack's video pipelines, one skeleton for every method:
//
//   frames (video file or image folder) -> background model or detector -> tracker
//     -> MOTChallenge rows (and detections) -> writers (tracks file, rendered video)
//
// The CLI's `vtrack track VIDEO` and Python's vtrack.track_video run exactly this code, so the
// same parameters give the same rows. A method is a FrameTracker (one BGR frame in, its tracks
// out) built by make_frame_tracker; adding a method means one FrameTracker and one entry in
// pipeline.cpp's method table.
//
// Methods and the config sections they read (parameters by the components' tables):
//   mb    KDE background model (mb-tbd paper Section 3.1)   background: KdeBackgroundParams
//         -> multi-Bernoulli TBD filter (Sections 3.2-4)     tracker:    MultiBernoulliParams
//         (after each frame the background model's closing is set to the tracker's, which is
//         relative to the people's learnt height, unless the tracker's closing_size is in pixels)
//   sir   KDE background model (as mb)                      background: KdeBackgroundParams
//         -> re-clustering SIR (particle-filters-human-     tracker:    ReclusteringSirParams
//            vehicle §2) on the foreground pixels of y
//   glmb  a people detector (detector "hog", required)      detector:   HogParams
//         -> delta-GLMB box tracker (BoxTracker)             tracker:    BoxTrackerParams
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vtrack/apps/config.hpp"
#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/filters/multi_bernoulli.hpp"
#include "vtrack/filters/reclustering_sir.hpp"
#include "vtrack/image/kde_background.hpp"

namespace vtrack::apps {

// The mb pipeline's background model: the KDE's defaults with illumination_compensation on.
// Eq. (10)'s intensity kernel turns a few per cent of global light change (clouds, a camera's
// auto exposure) into foreground over the whole image, and the multi-Bernoulli filter then births
// image-sized boxes on it (benchmarks/synthetic_people.py, scene seed 12: MOTA -0.09 without, 0.96
// with). On PETS09-S2L1, whose light drifts by at most 3 % over 100 frames, it changes y by
// 0.01 on average and costs MB, over tracker seeds 0-15, MOTA / IDF1 0.613 / 0.659 -> 0.609 /
// 0.646 on all frames, but almost all of it on 1-397, the half MB was tuned on (IDF1 0.706 ->
// 0.682; 398-795: 0.680 -> 0.677): the tuned defaults' luck on that half, not a loss on video.
inline image::KdeBackgroundParams mb_background_defaults() {
  image::KdeBackgroundParams p;
  p.illumination_compensation = true;
  return p;
}

// The sir pipeline's background model: the KDE's defaults with update_static on (start-up
// ghosts of the people in view at frame 0 are taken into the stack once they stop changing; the
// measurements are in benchmarks/sir_tuning.py's docstring).
inline image::KdeBackgroundParams sir_background_defaults() {
  image::KdeBackgroundParams p;
  p.update_static = true;
  return p;
}

struct PipelineParams {
  std::string method = "mb";  // "mb", "sir" or "glmb"
  // What gives glmb its boxes on a video: "hog" (OpenCV's HOG people detector). Required by
  // glmb, so that a detector added later cannot silently change what a command does; mb takes
  // none.
  std::string detector;
  image::KdeBackgroundParams background = mb_background_defaults();  // mb: "background"
  filters::MultiBernoulliParams mb;       // mb: section "tracker"
  filters::ReclusteringSirParams sir;     // sir: section "tracker"
  image::KdeBackgroundParams sir_background = sir_background_defaults();  // sir: "background"
  BoxTrackerParams box;                   // glmb: section "tracker"
  HogParams hog;                          // glmb: section "detector"
};

// The method names, in the order help texts list them.
const std::vector<std::string>& pipeline_methods();

// One config section of a method: its name and its parameters' current values.
struct PipelineSection {
  std::string name;
  ParameterValues values;
};
// The sections `params.method` reads, with the values in `params` (InvalidArgument for an
// unknown method).
std::vector<PipelineSection> pipeline_sections(const PipelineParams& params);

// Sets `name` on whichever section of the method has it (no two sections of a method share a
// name); InvalidType naming it, with the closest known name, when none has it. `seed` sets the
// tracker's seed.
void set_pipeline_parameter(PipelineParams& params, const std::string& name,
                            const core::ParameterValue& value);
// Applies a config: its seed to the tracker, each section to the method's section of that name
// (InvalidArgument for a section the method does not read; InvalidType for an unknown name).
void apply_config(PipelineParams& params, const Config& config);
// InvalidArgument for an unknown method, a detector the method does not take (or a missing one
// glmb needs), or a parameter out of range in a section the method reads.
void validate(const PipelineParams& params);

// The tracker stage of a video pipeline.
class FrameTracker {
 public:
  virtual ~FrameTracker() = default;
  // Consumes the next 8-bit BGR frame and returns the tracks at that frame.
  virtual const filters::Tracks& step(const cv::Mat& frame) = 0;
  // The detector's boxes at the last frame (frame field 0), or nullptr for a method without a
  // detector.
  virtual const std::vector<Detection>* detections() const { return nullptr; }
};

// The method's FrameTracker for width x height frames (validates `params`).
std::unique_ptr<FrameTracker> make_frame_tracker(const PipelineParams& params, int width,
                                                 int height);

struct PipelineResult {
  std::vector<TrackRow> tracks;       // every frame's tracks, frames from 1
  std::vector<Detection> detections;  // every frame's detections (methods with a detector)
  long long frames = 0;               // frames read
};

// Runs the pipeline over every frame of `input` (a video file or image folder). When `render`
// is not empty, writes the frames with each track's box in a colour of its own
// (AtomicVideoWriter: nothing is left behind on error). Parameters, the render path (not the
// input, in a writable folder: apps/output_paths.hpp) and the frame size the method needs are
// checked before any file is touched; IoError naming the frame for corrupt or truncated input.
// Long runs poll core::poll_interrupt() once per frame.
PipelineResult track_video(const std::string& input, const PipelineParams& params,
                           const std::string& render = {}, const FrameProgress& progress = {});

// Draws a box and its id onto `frame` in a colour derived from the id.
void draw_labelled_box(cv::Mat& frame, std::uint64_t id, double x, double y, double w, double h);

}  // namespace vtrack::apps

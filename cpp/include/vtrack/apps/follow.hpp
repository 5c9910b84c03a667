#pragma once
// `vtrack follow` and vtrack.follow: one object through a video with the colour particle filter
// or the part-based particle filter (filters/color_particle.hpp), initialised with a box on the
// frame `first`, one-pass (never re-initialised), as OpenCV's single-object trackers are used.
#include <string>
#include <vector>

#include "vtrack/apps/config.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/filters/color_particle.hpp"

namespace vtrack::apps {

struct FollowParams {
  std::string method = "color";  // "color" (the conventional PF) or "parts" (the part-based PF)
  filters::ColorParticleParams color;
  filters::PartParticleParams parts;
};
// The method's parameter table names (its `tracker` section of a config file).
// Sets `name` of the chosen method's parameters; InvalidArgument for an unknown name.
void set_follow_parameter(FollowParams& params, const std::string& name,
                          const core::ParameterValue& value);
// Applies a config file: its `tracker` section (and top-level seed) to the chosen method; any
// other section is an InvalidArgument naming it.
void apply_follow_config(FollowParams& params, const Config& config);
// The chosen method's parameters by name (what `vtrack params`-style output would print).
ParameterValues follow_parameter_values(const FollowParams& params);
// InvalidArgument for an unknown method or parameters out of range.
void validate(const FollowParams& params);

struct FollowRow {
  long long frame;       // 1-based, in the video's numbering
  double x, y, w, h;     // NaN when the tracker reported the target lost (ok = false)
};

// Follows the object of box `init` (x, y, w, h) on frame `first` (1-based) to frame `last`
// (inclusive; 0 = the end). The first row is the init box on frame `first`. InvalidArgument for
// a box of non-positive size or one that leaves the image, `first` < 1, `last` < `first`, and
// `first` past the end of the video; IoError for an unreadable video. With `render`, also writes
// the video of the followed frames with the box (and, for parts, each part's box, red when
// judged occluded), through a temporary file renamed on success.
std::vector<FollowRow> follow_video(const std::string& path, const filters::Box& init,
                                    const FollowParams& params, long long first = 1,
                                    long long last = 0, const std::string& render = "",
                                    const FrameProgress& progress = {});

// Writes rows as text, frame,x,y,w,h per line (boxes to 2 decimals, "nan" when lost), through
// write_text_atomically.
void write_follow(const std::string& path, const std::vector<FollowRow>& rows);

}  // namespace vtrack::apps

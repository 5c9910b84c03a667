#pragma once
// The `vtrack bgs` job: a video or image folder through the KDE background model
// (image/kde_background.hpp) into 8-bit y images, y * 255 rounded (255 = background).
#include <functional>
#include <string>

#include "vtrack/apps/video_source.hpp"  // FrameProgress
#include "vtrack/apps/video_writer.hpp"  // is_video_output
#include "vtrack/image/kde_background.hpp"

namespace vtrack::apps {

struct BgsResult {
  long long frames = 0;     // frames processed and written
  bool video = false;       // true: `output` is a video file; false: a folder of PNGs
};

// Called after every frame with (frames done, frames announced by the input or -1 if unknown).

// Reads `input` (VideoSource: a video file or an image folder), applies a KdeBackground with
// `params` and writes every y image to `output`:
//   * video (.avi/.mkv: Motion-JPEG, .mp4: MPEG-4 part 2; grey as 3 equal channels, the input's
//     frame rate or 25 fps when unknown): written to "<stem>.partial<ext>" next to `output` and
//     renamed to `output` only when every frame is done; on any error the partial file is
//     removed and `output` is left untouched (an existing file there is not replaced).
//   * folder (created if missing): one PNG per frame, "000000.png", "000001.png", ... (0-based
//     frame index), each written under a temporary name and renamed, so every file present is a
//     complete image. On a decode error the job stops and the images of the frames before it
//     stay: they are valid results of those frames.
// IoError (naming the 0-based frame index) for a corrupt or truncated input, IoError when the
// output cannot be written, InvalidArgument for bad `params` or an `output` that is the input
// (apps/output_paths.hpp; checked before any file is touched).
BgsResult run_background_subtraction(const std::string& input, const std::string& output,
                                     const image::KdeBackgroundParams& params,
                                     const FrameProgress& progress = {});

}  // namespace vtrack::apps

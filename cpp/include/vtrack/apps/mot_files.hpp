#pragma once
// MOTChallenge text files. Track files (gt.txt and trackers' output): one row per track and
// frame, frame,id,x,y,w,h,conf,-1,-1,-1. Detection files (det/det.txt): one detection per line,
//   frame,id,x,y,w,h[,conf[,x3d,y3d,z3d]]
// frames from 1, (x, y) the top-left corner and (w, h) the size of the box in pixels, the id
// column unused (-1). The reader is strict: every problem is reported with the file and line, so
// a bad file never turns into silently wrong tracks.
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "vtrack/filters/tracks.hpp"

namespace vtrack::apps {

struct Detection {
  long long frame = 0;  // 1-based
  double x = 0, y = 0, w = 0, h = 0;
  double confidence = 1.0;  // 1 when the file has no conf column
};

// Checks one detection: 1 <= frame <= core::kMaxFrame, finite box and confidence, w > 0 and
// h > 0, |x|, |y|, w, h <= core::kMaxCoordinate. Throws InvalidArgument whose message starts with
// `where` (e.g. "det.txt:12: ") and names the field and its value.
void validate_detection(const Detection& d, const std::string& where);

// Reads every detection of `path` with confidence >= min_confidence (a number; NaN is
// InvalidArgument), in file order. Blank lines are skipped; an empty file gives no detections.
// Bytes that are not UTF-8 are reported in messages as they are. IoError for a missing or
// unreadable file;
// InvalidArgument "path:line: ..." for a line with fewer than 6 or more than 10 fields, a field
// that is not a number, a non-integer frame, or a detection validate_detection rejects.
std::vector<Detection> read_detections(
    const std::string& path, double min_confidence = -std::numeric_limits<double>::infinity());

// Writes detections as MOTChallenge det rows (frame,-1,x,y,w,h,conf,-1,-1,-1) to "<path>.partial"
// renamed to `path` when complete (IoError on failure; nothing is left behind).
void write_detections(const std::string& path, const std::vector<Detection>& detections);

// One MOTChallenge track row: frame (1-based), id, box (left, top, width, height), confidence.
struct TrackRow {
  long long frame = 0;
  std::uint64_t id = 0;
  float x = 0, y = 0, w = 0, h = 0;
  double confidence = 0.0;
};

// Appends the rows of one frame's tracks (confidence = score). InvalidArgument for a track
// without an image box (NaN).
void append_rows(std::vector<TrackRow>& rows, long long frame, const filters::Tracks& tracks);

// Writes rows as MOTChallenge text, frame,id,x,y,w,h,conf,-1,-1,-1 with boxes to 2 decimals and
// conf to 4 (the one writer of track files: the CLI, Python and the batch mode use it), through
// write_text_atomically.
void write_mot(const std::string& path, const std::vector<TrackRow>& rows);

// Writes a text file through "<path>.partial", renamed to `path` once `write_lines` returned and
// the stream is flushed without error; the partial file is removed on any failure.
void write_text_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write_lines);

}  // namespace vtrack::apps

#include "vtrack/apps/mot_files.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "vtrack/apps/temporary_files.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/core/text_file.hpp"

namespace vtrack::apps {
namespace {

// A formatted row must fit its buffer whole: a cut row would silently merge with the next.
void check_line(int written, std::size_t size, long long frame) {
  if (written < 0 || static_cast<std::size_t>(written) >= size) {
    throw InvalidArgument("the row of frame " + std::to_string(frame) +
                          " has values too large to write as MOTChallenge text");
  }
}

}  // namespace

void validate_detection(const Detection& d, const std::string& where) {
  if (d.frame < 1) {
    throw InvalidArgument(where + "frame must be >= 1 (MOTChallenge frames are 1-based), got " +
                          std::to_string(d.frame));
  }
  const std::pair<const char*, double> fields[] = {
      {"x", d.x}, {"y", d.y}, {"w", d.w}, {"h", d.h}, {"conf", d.confidence}};
  for (const auto& [name, v] : fields) {
    if (!std::isfinite(v)) throw InvalidArgument(where + name + " must be finite, got " + value_text(v));
  }
  if (!(d.w > 0)) throw InvalidArgument(where + "w must be > 0, got " + value_text(d.w));
  if (!(d.h > 0)) throw InvalidArgument(where + "h must be > 0, got " + value_text(d.h));
  for (const auto& [name, v] : fields) {
    if (std::string(name) != "conf" && std::fabs(v) > core::kMaxCoordinate) {
      throw InvalidArgument(where + name + " must be within +-" + value_text(core::kMaxCoordinate) +
                            " pixels, got " + value_text(v));
    }
  }
  if (d.frame > core::kMaxFrame) {
    throw InvalidArgument(where + "frame must be <= " + std::to_string(core::kMaxFrame) + ", got " +
                          std::to_string(d.frame));
  }
}

std::vector<Detection> read_detections(const std::string& path, double min_confidence) {
  if (std::isnan(min_confidence)) {
    throw InvalidArgument("min_confidence must be a number (-inf keeps every row), got nan");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw IoError(std::filesystem::exists(path, ec)
                      ? "detection file '" + path + "' is not a regular file"
                      : "no such detection file: '" + path + "'");
  }
  std::ifstream in(path);
  if (!in) throw IoError("cannot read detection file '" + path + "'");
  static const char* const names[] = {"frame", "id", "x", "y", "w", "h", "conf", "x3d", "y3d", "z3d"};
  std::vector<Detection> out;
  std::string line;
  long long number = 0;
  while (std::getline(in, line)) {
    if ((++number & 4095) == 0) core::poll_interrupt();  // files may hold millions of rows
    if (core::trimmed(line).empty()) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    const std::vector<std::string> fields = core::comma_fields(line);
    if (fields.size() < 6 || fields.size() > 10) {
      throw InvalidArgument(where + "expected 6 to 10 comma-separated fields "
                            "(frame,id,x,y,w,h[,conf,...]), got " + std::to_string(fields.size()));
    }
    double v[10];
    for (std::size_t i = 0; i < fields.size(); ++i) v[i] = core::number_field(fields[i], names[i], where);
    if (!(std::isfinite(v[0]) && v[0] == std::floor(v[0]) &&
          std::fabs(v[0]) <= static_cast<double>(core::kMaxFrame))) {
      throw InvalidArgument(where + "frame must be an integer, got '" + core::trimmed(fields[0]) + "'");
    }
    Detection d{static_cast<long long>(v[0]), v[2], v[3], v[4], v[5],
                fields.size() > 6 ? v[6] : 1.0};
    validate_detection(d, where);
    if (d.confidence >= min_confidence) out.push_back(d);
  }
  if (in.bad()) throw IoError("error reading detection file '" + path + "'");
  return out;
}

void write_text_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write_lines) {
  const std::filesystem::path target(path);
  const std::filesystem::path partial = partial_path(target);
  TemporaryFile registered(partial.string());
  {
    std::ofstream out(partial);
    if (!out) throw IoError("cannot write '" + partial.string() + "'");
    try {
      write_lines(out);
    } catch (...) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(partial, ec);
      throw;
    }
    out.close();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(partial, ec);
      throw IoError("cannot write '" + partial.string() + "'");
    }
  }
  rename_or_throw(partial, target);
}

void write_detections(const std::string& path, const std::vector<Detection>& detections) {
  write_text_atomically(path, [&](std::ostream& out) {
    char line[512];
    for (const auto& d : detections) {
      const int n = std::snprintf(line, sizeof line, "%lld,-1,%.3f,%.3f,%.3f,%.3f,%.6g,-1,-1,-1\n",
                                  d.frame, d.x, d.y, d.w, d.h, d.confidence);
      check_line(n, sizeof line, d.frame);
      out << line;
    }
  });
}

void append_rows(std::vector<TrackRow>& rows, long long frame, const filters::Tracks& tracks) {
  for (const auto& t : tracks) {
    if (std::isnan(t.x) || std::isnan(t.y) || std::isnan(t.w) || std::isnan(t.h)) {
      throw InvalidArgument("track " + std::to_string(t.id) +
                            " has no image box: MOTChallenge rows need one");
    }
    rows.push_back({frame, t.id, static_cast<float>(t.x), static_cast<float>(t.y),
                    static_cast<float>(t.w), static_cast<float>(t.h), t.score});
  }
}

void write_mot(const std::string& path, const std::vector<TrackRow>& rows) {
  write_text_atomically(path, [&](std::ostream& out) {
    char line[512];
    for (const auto& r : rows) {
      const int n = std::snprintf(line, sizeof line, "%lld,%llu,%.2f,%.2f,%.2f,%.2f,%.4f,-1,-1,-1\n",
                                  r.frame, static_cast<unsigned long long>(r.id), r.x, r.y, r.w,
                                  r.h, r.confidence);
      check_line(n, sizeof line, r.frame);
      out << line;
    }
  });
}

}  // namespace vtrack::apps

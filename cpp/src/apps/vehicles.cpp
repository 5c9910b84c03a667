#include "vtrack/apps/vehicles.hpp"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "vtrack/apps/mot_files.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/limits.hpp"

namespace vtrack::apps {
namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

double number(const std::string& field, const std::string& name, const std::string& where) {
  const std::string text = trimmed(field);
  char* end = nullptr;
  const double v = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw InvalidArgument(where + name + " is not a number: '" + text + "'");
  }
  if (!std::isfinite(v)) throw InvalidArgument(where + name + " must be finite, got " + text);
  return v;
}

int whole(const std::string& field, const char* name, const std::string& where, int lowest) {
  const double v = number(field, name, where);
  if (v != std::floor(v) || v < lowest || v > INT_MAX) {
    throw InvalidArgument(where + name + " must be an integer >= " + std::to_string(lowest) + ", got '" +
                          trimmed(field) + "'");
  }
  return static_cast<int>(v);
}

VehicleSilhouette parse_line(const std::string& line, const std::string& where) {
  std::vector<std::string> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  const std::size_t n = fields.size();
  if (n < 6 || n % 2 != 0) {
    throw InvalidArgument(where + "expected frame,vehicle_id,x,y,w,h or frame,vehicle_id,x1,y1,...,xn,yn "
                          "(n >= 3), got " + std::to_string(n) + " fields");
  }
  VehicleSilhouette s;
  s.frame = whole(fields[0], "frame", where, 1);
  s.vehicle_id = whole(fields[1], "vehicle_id", where, 0);
  s.is_box = n == 6;
  s.points.resize(2, static_cast<Eigen::Index>((n - 2) / 2));
  for (std::size_t i = 2; i < n; ++i) {
    const std::string name = s.is_box ? std::string(i == 2 ? "x" : i == 3 ? "y" : i == 4 ? "w" : "h")
                                      : (i % 2 == 0 ? "x" : "y") + std::to_string((i - 2) / 2 + 1);
    const double v = number(fields[i], name, where);
    if (std::fabs(v) > core::kMaxCoordinate) {
      throw InvalidArgument(where + name + " must be within +-1e9 pixels, got " + trimmed(fields[i]));
    }
    s.points(static_cast<Eigen::Index>(i % 2), static_cast<Eigen::Index>((i - 2) / 2)) = v;
  }
  if (s.is_box && !(s.points(0, 1) > 0.0 && s.points(1, 1) > 0.0)) {
    throw InvalidArgument(where + "the box's w and h must be > 0, got " + trimmed(fields[4]) + ", " +
                          trimmed(fields[5]));
  }
  return s;
}

std::string fixed3(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

// A CSV field, quoted (RFC 4180) when a models file gave a class name with a comma or a quote.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::vector<VehicleSilhouette> read_vehicle_observations(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw IoError(std::filesystem::exists(path, ec) ? "observations file '" + path + "' is not a regular file"
                                                    : "no such observations file: '" + path + "'");
  }
  std::ifstream in(path);
  if (!in) throw IoError("cannot read observations file '" + path + "'");
  std::vector<VehicleSilhouette> out;
  std::string line;
  long long number_of_line = 0;
  while (std::getline(in, line)) {
    if ((++number_of_line & 4095) == 0) core::poll_interrupt();
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#') continue;
    if (number_of_line == 1 && text.rfind("frame", 0) == 0) continue;  // a header
    out.push_back(parse_line(text, path + ":" + std::to_string(number_of_line) + ": "));
  }
  if (in.bad()) throw IoError("error reading observations file '" + path + "'");
  return out;
}

std::vector<filters::VehicleEstimate> estimate_vehicles(filters::VehicleDimensionEstimator& estimator,
                                                        const std::vector<VehicleSilhouette>& silhouettes) {
  std::size_t done = 0;
  for (const auto& s : silhouettes) {
    if ((++done & 255) == 0) core::poll_interrupt();
    try {
      if (s.is_box) {
        estimator.update_box(s.vehicle_id, s.frame, s.points(0, 0), s.points(1, 0), s.points(0, 1), s.points(1, 1));
      } else {
        estimator.update_polygon(s.vehicle_id, s.frame, s.points);
      }
    } catch (const InvalidArgument& e) {
      throw InvalidArgument("vehicle " + std::to_string(s.vehicle_id) + ", frame " + std::to_string(s.frame) +
                            ": " + e.what());
    }
  }
  return estimator.estimates();
}

void write_vehicles_csv(const std::string& path, const std::vector<filters::VehicleEstimate>& estimates) {
  write_text_atomically(path, [&](std::ostream& out) {
    out << "vehicle_id,class,light_heavy,W,H,L,first_frame,last_frame,frames_used\n";
    for (const auto& e : estimates) {
      out << e.vehicle_id << ',';
      if (e.valid) {
        out << csv_field(e.class_name) << ',' << (e.heavy ? "heavy" : "light") << ',' << fixed3(e.dimensions(0)) << ','
            << fixed3(e.dimensions(1)) << ',' << fixed3(e.dimensions(2));
      } else {
        out << "not_fully_in_view,unknown,,,";
      }
      out << ',' << e.first_frame << ',' << e.last_frame << ',' << e.frames_used << '\n';
    }
  });
}

}  // namespace vtrack::apps

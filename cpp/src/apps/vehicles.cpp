#include "vtrack/apps/vehicles.hpp"

#include <algorithm>
#include <climits>
#include <limits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <memory>
#include <optional>
#include <set>

#include <opencv2/imgproc.hpp>

#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/limits.hpp"
#include "vtrack/core/text_file.hpp"

namespace vtrack::apps {
namespace {

// The whole field as a finite number.
double number(const std::string& field, const std::string& name, const std::string& where) {
  const double v = core::number_field(field, name, where);
  if (!std::isfinite(v)) throw InvalidArgument(where + name + " must be finite, got " + core::trimmed(field));
  return v;
}

int whole(const std::string& field, const char* name, const std::string& where, int lowest) {
  const double v = number(field, name, where);
  if (v != std::floor(v) || v < lowest || v > INT_MAX) {
    throw InvalidArgument(where + name + " must be an integer >= " + std::to_string(lowest) + ", got '" +
                          core::trimmed(field) + "'");
  }
  return static_cast<int>(v);
}

VehicleSilhouette parse_line(const std::string& line, const std::string& where) {
  const std::vector<std::string> fields = core::comma_fields(line);
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
      throw InvalidArgument(where + name + " must be within +-1e9 pixels, got " + core::trimmed(fields[i]));
    }
    s.points(static_cast<Eigen::Index>(i % 2), static_cast<Eigen::Index>((i - 2) / 2)) = v;
  }
  if (s.is_box && !(s.points(0, 1) > 0.0 && s.points(1, 1) > 0.0)) {
    throw InvalidArgument(where + "the box's w and h must be > 0, got " + core::trimmed(fields[4]) + ", " +
                          core::trimmed(fields[5]));
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
    const std::string text = core::trimmed(line);
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

// ---- video -> vehicles ----------------------------------------------------------------------------

namespace vtrack::apps {

const core::ParameterTable<VehicleBlobParams>& VehicleBlobParams::table() {
  using P = VehicleBlobParams;
  static const auto t = core::ParameterTable<P>()
                            .add("foreground_threshold", &P::foreground_threshold)
                            .add("blob_closing", &P::blob_closing)
                            .add("min_area", &P::min_area)
                            .add("min_overlap", &P::min_overlap)
                            .add("merge_min_share", &P::merge_min_share)
                            .add("foot_gate", &P::foot_gate)
                            .add("lane_split_gap", &P::lane_split_gap)
                            .add("lane_split_hold", &P::lane_split_hold)
                            .add("hidden_horizon", &P::hidden_horizon)
                            .add("hidden_max_passage", &P::hidden_max_passage)
                            .add("hold_views", &P::hold_views)
                            .add("lost_memory", &P::lost_memory)
                            .add("confirm_frames", &P::confirm_frames)
                            .add("min_travel", &P::min_travel)
                            .add("stitch_gap", &P::stitch_gap)
                            .add("max_aspect", &P::max_aspect)
                            .add("thin_views", &P::thin_views);
  return t;
}

void validate(const VehicleBlobParams& p) {
  require(p.foreground_threshold > 0.0 && p.foreground_threshold <= 1.0, "foreground_threshold",
          p.foreground_threshold, "in (0, 1]");
  require(p.blob_closing >= 0 && p.blob_closing <= 255 && (p.blob_closing <= 1 || p.blob_closing % 2 == 1),
          "blob_closing", p.blob_closing, "0 (auto), 1 (off) or an odd number up to 255");
  require(p.min_area >= 0, "min_area", p.min_area, ">= 0 (0: auto)");
  require(p.min_overlap > 0.0 && p.min_overlap <= 1.0, "min_overlap", p.min_overlap, "in (0, 1]");
  require(p.merge_min_share >= 0.0 && p.merge_min_share <= 1.0, "merge_min_share",
          p.merge_min_share, "in [0, 1]");
  require(p.foot_gate >= 0.0 && std::isfinite(p.foot_gate), "foot_gate", p.foot_gate,
          "a finite number >= 0 (a share of the predicted box's height; 0: off)");
  require(p.lane_split_gap >= 0.0 && std::isfinite(p.lane_split_gap), "lane_split_gap", p.lane_split_gap,
          "a finite number of metres >= 0 (0: off)");
  require(p.lane_split_hold >= 0.0 && p.lane_split_hold <= 60.0, "lane_split_hold", p.lane_split_hold,
          "seconds in [0, 60]");
  require(p.hidden_horizon >= 0.0 && std::isfinite(p.hidden_horizon), "hidden_horizon", p.hidden_horizon,
          "a finite number >= 0 (a share of a track's passage; 0: off)");
  require(p.hidden_max_passage >= 0.0 && std::isfinite(p.hidden_max_passage), "hidden_max_passage",
          p.hidden_max_passage, "a finite number of seconds >= 0 (0: no limit)");
  require(p.lost_memory >= 0 && p.lost_memory <= 1000, "lost_memory", p.lost_memory, "in [0, 1000]");
  require(p.min_travel >= 0.0 && std::isfinite(p.min_travel), "min_travel", p.min_travel,
          "a finite number of metres >= 0 (0: off)");
  require(p.stitch_gap >= 0.0 && p.stitch_gap <= 60.0, "stitch_gap", p.stitch_gap, "seconds in [0, 60]");
  require(p.max_aspect >= 0.0 && std::isfinite(p.max_aspect), "max_aspect", p.max_aspect,
          "a finite ratio >= 0 (length / width; 0: off)");
  require(p.thin_views >= 0 && p.thin_views <= 1000, "thin_views", p.thin_views, "in [0, 1000] (0: off)");
  require(p.confirm_frames >= 1 && p.confirm_frames <= 1000, "confirm_frames", p.confirm_frames, "in [1, 1000]");
}

VehicleBlobParams blob_sizes_for(VehicleBlobParams p, double focal_px) {
  constexpr double kReferenceFocal = 900.0, kClosing = 3.0, kMinArea = 150.0;
  const double scale = focal_px / kReferenceFocal;
  if (p.blob_closing == 0) {
    const int side = static_cast<int>(std::lround(kClosing * scale));
    p.blob_closing = std::clamp(side % 2 == 1 ? side : side + 1, 1, 255);
  }
  if (p.min_area == 0) p.min_area = std::max(1, static_cast<int>(std::lround(kMinArea * scale * scale)));
  return p;
}

void validate(const VehiclePipelineParams& p) {
  image::validate(p.background);
  validate(p.blobs);
  filters::validate(p.estimator);
}

void set_vehicle_parameter(VehiclePipelineParams& p, const std::string& name, const core::ParameterValue& value) {
  if (filters::VehicleEstimatorParams::table().set(p.estimator, name, value)) return;
  if (VehicleBlobParams::table().set(p.blobs, name, value)) return;
  if (image::KdeBackgroundParams::table().set(p.background, name, value)) return;
  std::vector<std::string> names = filters::VehicleEstimatorParams::table().names();
  for (const auto& n : VehicleBlobParams::table().names()) names.push_back(n);
  for (const auto& n : image::KdeBackgroundParams::table().names()) names.push_back(n);
  core::throw_unknown_parameter(name, "vehicles", names);
}

void apply_vehicle_config(VehiclePipelineParams& p, const Config& config) {
  for (const auto& [section, values] : config.sections) {
    if (section == "background") core::set_parameters(p.background, values, "background");
    else if (section == "blobs") core::set_parameters(p.blobs, values, "blobs");
    else if (section == "estimator") core::set_parameters(p.estimator, values, "estimator");
    else {
      throw InvalidArgument("config file '" + config.path + "': vehicles reads the sections background, blobs "
                            "and estimator, got '" + section + "'");
    }
  }
  if (config.seed) p.estimator.seed = *config.seed;
}

std::vector<PipelineSection> vehicle_sections(const VehiclePipelineParams& p) {
  return {{"background", image::KdeBackgroundParams::table().values(p.background)},
          {"blobs", VehicleBlobParams::table().values(p.blobs)},
          {"estimator", filters::VehicleEstimatorParams::table().values(p.estimator)}};
}

filters::VehicleEstimate vehicle_answer(filters::VehicleEstimate own,
                                        const std::function<filters::VehicleEstimate()>& joined,
                                        const VehicleBlobParams& p) {
  const auto one_vehicle = [&p](const filters::VehicleEstimate& e) {
    return e.valid && (p.max_aspect <= 0.0 || e.dimensions(2) <= p.max_aspect * e.dimensions(0));
  };
  if (!own.valid) return joined();
  const bool own_shape = one_vehicle(own), thin = own.frames_used <= p.thin_views;
  if (own_shape && !thin) return own;
  filters::VehicleEstimate fallback = joined();
  if (!one_vehicle(fallback)) return own;
  constexpr int kThickerBy = 3;  // a thin own answer stands unless the joined one rests on this many times its views
  return own_shape && fallback.frames_used < kThickerBy * own.frames_used ? own : fallback;
}

namespace {

struct Blob {
  int label = 0;  // its component in the labels image
  cv::Rect box;
  std::vector<cv::Point> contour;
  // The silhouette's lowest image point and where it meets the road (metres), when that point is
  // a ground point of the vehicle: for a cuboid on the road seen by a camera with no roll the
  // lowest image point is a bottom corner (the one nearest the camera), unless the image border
  // cuts the silhouette there.
  cv::Point2d foot;
  Eigen::Vector2d ground = Eigen::Vector2d::Zero();
  bool has_ground = false;
  bool split = false;       // a part of a split component: its outline may hold the other vehicle's
  int cut_streak = 0;       // consecutive frames up to this one in which this blob was split
  bool cut_whole = false;   // blobs_to_track(): split, but tracked whole (its outline may be two vehicles')
  std::vector<Blob> parts;  // split_across_lanes(): the component's parts when it was split, else none
};

// The lowest contour point (the mean x of the lowest row's points) and its road point; no ground
// point when it lies on the image's outermost pixels (cut by the border) or at/above the horizon.
void find_ground(Blob& blob, const models::Camera& camera, int width, int height) {
  int lowest = INT_MIN;
  double sum_x = 0.0;
  int n = 0;
  for (const auto& p : blob.contour) {
    if (p.y > lowest) lowest = p.y, sum_x = 0.0, n = 0;
    if (p.y == lowest) sum_x += p.x, ++n;
  }
  if (n == 0) return;
  blob.foot = {sum_x / n, static_cast<double>(lowest)};
  if (lowest >= height - 1 || blob.foot.x < 1.0 || blob.foot.x > width - 2.0) return;
  try {
    blob.ground = camera.image_to_road_points(Eigen::Vector2d(blob.foot.x, blob.foot.y)).col(0);
    blob.has_ground = true;
  } catch (const InvalidArgument&) {
    // At or above the horizon: no road point.
  }
}

// The lowest pixel of each column of component `label` inside `box` and where it meets the road
// across it (metres along the camera's lateral axis); empty when the component touches the image's
// left, right or bottom edge (the border then cuts its bottom edges: the lowest pixels of the
// columns beside the cut lie on its sides, above the road) or a lowest pixel lies at or above the
// horizon.
struct ColumnFoot {
  int x;
  double lateral;
};
std::vector<ColumnFoot> lower_outline(const cv::Mat& labels, int label, const cv::Rect& box,
                                      const models::Camera& camera) {
  if (box.x <= 0 || box.x + box.width >= labels.cols || box.y + box.height >= labels.rows) return {};
  std::vector<int> xs, ys;
  for (int x = box.x; x < box.x + box.width; ++x) {
    for (int y = box.y + box.height - 1; y >= box.y; --y) {
      if (labels.at<int>(y, x) == label) {
        xs.push_back(x), ys.push_back(y);
        break;
      }
    }
  }
  Eigen::Matrix2Xd pixels(2, xs.size());
  for (std::size_t j = 0; j < xs.size(); ++j) pixels.col(j) << xs[j], ys[j];
  std::vector<ColumnFoot> feet;
  try {
    const Eigen::Matrix2Xd road = camera.image_to_road_points(pixels);
    const Eigen::Vector2d across = camera.lateral_axis().head<2>();
    for (std::size_t j = 0; j < xs.size(); ++j) feet.push_back({xs[j], road.col(j).dot(across)});
  } catch (const InvalidArgument&) {
    feet.clear();  // at or above the horizon: not a vehicle on the road
  }
  return feet;
}

// The lateral position across the road that parts a blob's lower outline (lower_outline()) into
// two vehicles in different lanes, or nullopt (header: lane_split_gap). A cuboid on the road, seen
// by a camera with no roll, has the images of its bottom edges as its lower outline: they meet
// the road within its width W (<= 2.6 m) across it, sweeping it continuously along the front or
// rear edge. Two vehicles abreast in adjacent lanes leave a gap across the road of a lane's width
// less their half widths (>= ~1 m on 3.5 m lanes) between their lower outlines. So the feet are
// parted at the widest gap of `gap` metres or more between their sorted lateral positions with at
// least a sixth of the columns (and 3) on either side, each side within a vehicle's width: the
// widest such gap (any_gap = false: nullopt if its sides are not), or the widest of those whose
// sides are (any_gap = true).
std::optional<double> lane_threshold(const std::vector<ColumnFoot>& feet, double gap, bool any_gap) {
  const int n = static_cast<int>(feet.size());
  const int min_side = std::max(3, n / 6);
  if (gap <= 0.0 || n < 2 * min_side) return std::nullopt;
  std::vector<double> sorted;
  for (const auto& f : feet) sorted.push_back(f.lateral);
  std::sort(sorted.begin(), sorted.end());
  constexpr double kWidestVehicle = 3.0;
  const auto one_vehicle = [&](int begin, int end) { return sorted[end - 1] - sorted[begin] <= kWidestVehicle; };
  int widest = -1;
  for (int j = min_side; j <= n - min_side; ++j) {
    const double g = sorted[j] - sorted[j - 1];
    if (g < gap || (widest >= 0 && g <= sorted[widest] - sorted[widest - 1])) continue;
    if (!any_gap || (one_vehicle(0, j) && one_vehicle(j, n))) widest = j;
  }
  if (widest < 0 || !one_vehicle(0, widest) || !one_vehicle(widest, n)) return std::nullopt;
  return 0.5 * (sorted[widest] + sorted[widest - 1]);
}

// The columns of a blob that hold one lane's vehicle, the rest of its columns holding the other
// lane's (lane_cut()): [begin, end) of the image (end INT_MAX: to the blob's right end). `middle`:
// the near vehicle's columns inside the far one's (the far vehicle shows on both sides of it).
struct LaneCut {
  int begin = 0;
  int end = 0;
  bool middle = false;
};

// far_before[j]: the far vehicle's feet among feet[0, j) (feet in increasing x), the sides parted
// at `threshold`, the near one the side nearer `camera_lateral` (the camera's position across the
// road).
std::vector<int> far_before(const std::vector<ColumnFoot>& feet, double threshold, double camera_lateral) {
  const bool high_is_near = camera_lateral > threshold;
  std::vector<int> out(feet.size() + 1, 0);
  for (std::size_t j = 0; j < feet.size(); ++j) out[j + 1] = out[j] + ((feet[j].lateral > threshold) != high_is_near);
  return out;
}

// The fewest misplaced columns, and the cut, of two runs, one left of the other: a cut before foot
// j, the far side left of it or right of it.
std::pair<int, LaneCut> two_runs(const std::vector<ColumnFoot>& feet, const std::vector<int>& far_before) {
  const int n = static_cast<int>(feet.size()), far_total = far_before[n];
  std::pair<int, LaneCut> best{n + 1, {}};
  for (int j = 1; j < n; ++j) {
    const int near_before = j - far_before[j], far_after = far_total - far_before[j];
    const int errors = std::min(near_before + far_after, far_before[j] + (n - j - far_after));
    if (errors < best.first) best = {errors, {feet[j].x, INT_MAX, false}};
  }
  return best;
}

// The fewest misplaced columns, and the cut, of three runs, the near vehicle's feet[j1, j2) between
// two of the far one's of at least 3 columns each: misplaced = far ones inside + near ones outside
// = (j1 - 2 far_before[j1]) + (2 far_before[j2] - j2) + n - far_total, the first term minimised
// over j1 < j2 as j2 grows.
std::pair<int, LaneCut> three_runs(const std::vector<ColumnFoot>& feet, const std::vector<int>& far_before) {
  const int n = static_cast<int>(feet.size()), far_total = far_before[n];
  std::pair<int, LaneCut> best{n + 1, {}};
  int best_left = INT_MAX, best_j1 = 0;
  for (int j2 = 4; j2 <= n - 3; ++j2) {
    const int j1 = j2 - 1;
    if (j1 - 2 * far_before[j1] < best_left) best_left = j1 - 2 * far_before[j1], best_j1 = j1;
    const int errors = best_left + 2 * far_before[j2] - j2 + n - far_total;
    if (errors < best.first) best = {errors, {feet[best_j1].x, feet[j2].x, true}};
  }
  return best;
}

// Where a blob's lower outline parts into two vehicles in different lanes, or nullopt. The sides
// (lane_threshold()) must lie in runs of columns, but for a tenth of the columns (pixel noise at the
// seams). Two runs, one left of the other, parted at the widest gap: vehicles abreast. Failing
// that, three runs, the near vehicle's between two of the far one's: a long far vehicle showing on
// both sides of a shorter near one that hides its middle (far_side_right seed 2500: a car before an
// articulated lorry, one blob for its whole passage). For these, a twentieth of the columns at
// either end are left out (a blob's outermost columns may end on a vertical edge above the road:
// 5 m off in the last of that blob's 40; up to 13 m in the last 8 of 286 of pole_hd seed 2700's bus
// and car) and the gap is the widest whose sides are each one vehicle's (the bus's own outline
// shows a 1.04 m gap where the car hides its corner). Only where the two-run rule finds no cut:
// with its end columns and gaps for every blob the two-run rule cut single grey vehicles whose
// mask has holes, and heavies were lost (benchmarks/vehicles.py). The far vehicle's feet between
// two runs of the near one's would be two near vehicles: no clean cut, and the blob stays whole
// (the tracker's merges handle it).
std::optional<LaneCut> lane_cut(std::vector<ColumnFoot> feet, double gap, double camera_lateral) {
  if (const auto threshold = lane_threshold(feet, gap, false)) {
    const auto [errors, cut] = two_runs(feet, far_before(feet, *threshold, camera_lateral));
    if (errors <= static_cast<int>(feet.size()) / 10) return cut;
  }
  const auto end_columns = static_cast<std::ptrdiff_t>(feet.size() / 20);
  feet.erase(feet.end() - end_columns, feet.end());
  feet.erase(feet.begin(), feet.begin() + end_columns);
  const auto threshold = lane_threshold(feet, gap, true);
  if (!threshold) return std::nullopt;
  const auto far = far_before(feet, *threshold, camera_lateral);
  const auto [errors, cut] = three_runs(feet, far);
  if (errors < two_runs(feet, far).first && errors <= static_cast<int>(feet.size()) / 10) return cut;
  return std::nullopt;
}

// The colour histogram (8 x 8 x 8 BGR bins, +1 per bin) of `frame` over `mask` within `box`,
// normalised to a probability.
cv::Mat colour_histogram(const cv::Mat& frame, const cv::Rect& box, const cv::Mat& mask) {
  cv::Mat hist;
  const int channels[] = {0, 1, 2}, bins[] = {8, 8, 8};
  const float range[] = {0.f, 256.f};
  const float* ranges[] = {range, range, range};
  cv::Mat roi = frame(box);
  cv::calcHist(&roi, 1, channels, mask, hist, 3, bins, ranges);
  hist += 1.0f;
  return hist / cv::sum(hist)[0];
}

// After a lane cut, the far vehicle's body above the near one in the near vehicle's columns: a
// pixel of the near part above its lowest quarter whose colour is twice as likely under the far
// part's colours as under the near part's lowest quarter (surely the near vehicle's) goes to the
// far part's label.
void give_far_body_back(cv::Mat& labels, const cv::Mat& frame, const cv::Rect& near_box, int near_label,
                        const cv::Rect& far_box, int far_label) {
  const cv::Mat far_hist = colour_histogram(frame, far_box, labels(far_box) == far_label);
  const int seed_top = near_box.y + near_box.height * 3 / 4;
  const cv::Rect seed(near_box.x, seed_top, near_box.width, near_box.y + near_box.height - seed_top);
  const cv::Mat near_hist = colour_histogram(frame, seed, labels(seed) == near_label);
  for (int y = near_box.y; y < seed_top; ++y) {
    for (int x = near_box.x; x < near_box.x + near_box.width; ++x) {
      if (labels.at<int>(y, x) != near_label) continue;
      const cv::Vec3b c = frame.at<cv::Vec3b>(y, x);
      const int b = c[0] / 32, g = c[1] / 32, r = c[2] / 32;
      if (far_hist.at<float>(b, g, r) > 2.0f * near_hist.at<float>(b, g, r)) labels.at<int>(y, x) = far_label;
    }
  }
}

// Component i's bounding box from cv::connectedComponentsWithStats' stats.
cv::Rect component_box(const cv::Mat& stats, int i) {
  return {stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP), stats.at<int>(i, cv::CC_STAT_WIDTH),
          stats.at<int>(i, cv::CC_STAT_HEIGHT)};
}

// The pieces of component `label`'s pixels within `box` of at least min_area pixels, the first
// keeping the label and the others each under a new one, with their boxes; the component whole
// when it is in one such piece. (Smaller pieces keep the label: blob_of() takes the longest
// outline.)
std::vector<std::pair<int, cv::Rect>> pieces_of(cv::Mat& labels, int label, const cv::Rect& box, int min_area,
                                                int& next_label) {
  cv::Mat piece, stats, centroids;
  const int n = cv::connectedComponentsWithStats(labels(box) == label, piece, stats, centroids, 8, CV_32S);
  std::vector<std::pair<int, cv::Rect>> out;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < min_area) continue;
    const int piece_label = out.empty() ? label : next_label++;
    labels(box).setTo(piece_label, piece == i);
    out.emplace_back(piece_label, component_box(stats, i) + box.tl());
  }
  if (out.size() <= 1) return {{label, box}};
  return out;
}

// Splits component `label` (box `box`) at lane_cut()'s columns, the cut's columns under a new
// label, and gives the far vehicle's body above the near one back to the far part
// (give_far_body_back(); the near part is the one between the far one's runs, or else the one
// reaching lower in the image). Then splits the near part again (three lanes' vehicles), and the
// far part of two runs again, or one of three into its pieces (pieces_of()): a far vehicle seen on
// both sides of the near one is one piece when its body shows above the near one, but two far
// vehicles, one either side of the near one (a clump of traffic), are two. The parts' labels with
// their boxes, or the component whole. A part under min_area pixels is no vehicle.
std::vector<std::pair<int, cv::Rect>> split_across_lanes(cv::Mat& labels, const cv::Mat& frame, int label,
                                                         const cv::Rect& box, const models::Camera& camera,
                                                         double gap, int min_area, int& next_label) {
  const double camera_lateral = camera.centre().dot(camera.lateral_axis());
  const auto cut = lane_cut(lower_outline(labels, label, box, camera), gap, camera_lateral);
  if (!cut) return {{label, box}};
  const cv::Rect cut_cols(cut->begin, box.y, std::min(cut->end, box.x + box.width) - cut->begin, box.height);
  const cv::Mat inside = labels(cut_cols) == label;
  const int inside_area = cv::countNonZero(inside);
  if (inside_area < min_area || cv::countNonZero(labels(box) == label) - inside_area < min_area) return {{label, box}};
  const int new_label = next_label++;
  labels(cut_cols).setTo(new_label, inside);
  const auto box_of = [&](int l) { return cv::boundingRect(labels(box) == l) + box.tl(); };
  cv::Rect old_box = box_of(label), new_box = box_of(new_label);
  if (frame.type() == CV_8UC3) {
    if (cut->middle || new_box.br().y > old_box.br().y) {
      give_far_body_back(labels, frame, new_box, new_label, old_box, label);
    } else {
      give_far_body_back(labels, frame, old_box, label, new_box, new_label);
    }
    old_box = box_of(label), new_box = box_of(new_label);
    if (old_box.area() == 0 || new_box.area() == 0) return {{label, box}};
  }
  auto parts = split_across_lanes(labels, frame, new_label, new_box, camera, gap, min_area, next_label);
  auto more = cut->middle ? pieces_of(labels, label, old_box, min_area, next_label)
                          : split_across_lanes(labels, frame, label, old_box, camera, gap, min_area, next_label);
  parts.insert(parts.end(), more.begin(), more.end());
  return parts;
}

// One blob of component `label` within `box`: its outer contour (pixel centres; the longest one)
// and ground point; nullopt when it has no contour.
std::optional<Blob> blob_of(const cv::Mat& labels, int label, const cv::Rect& box, const models::Camera& camera) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(labels(box) == label, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE, box.tl());
  if (contours.empty()) return std::nullopt;
  std::size_t best = 0;
  for (std::size_t c = 1; c < contours.size(); ++c) {
    if (contours[c].size() > contours[best].size()) best = c;
  }
  Blob blob;
  blob.label = label;
  blob.box = box;
  blob.contour = std::move(contours[best]);
  find_ground(blob, camera, labels.cols, labels.rows);
  return blob;
}

// Connected components of the closed foreground of at least min_area pixels as blobs, each with
// its parts when split across lanes (split_across_lanes(); the parts' pixels carry their own
// labels until associate() takes the component whole: restore_whole()).
std::vector<Blob> find_blobs(const cv::Mat& mask, const cv::Mat& frame, const VehicleBlobParams& p,
                             const models::Camera& camera, cv::Mat& labels) {
  cv::Mat stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int next_label = n;
  std::vector<Blob> out;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < p.min_area) continue;
    const cv::Rect component = component_box(stats, i);
    auto whole = blob_of(labels, i, component, camera);
    if (!whole) continue;
    const auto parts = split_across_lanes(labels, frame, i, component, camera, p.lane_split_gap, 4 * p.min_area, next_label);
    for (std::size_t k = 0; parts.size() > 1 && k < parts.size(); ++k) {
      if (auto part = blob_of(labels, parts[k].first, parts[k].second, camera)) {
        part->split = true;
        whole->parts.push_back(std::move(*part));
      }
    }
    out.push_back(std::move(*whole));
  }
  return out;
}

// Each split blob's cut_streak: 1 + that of the last frame's split blob it overlaps most (0 if
// none); `before` becomes this frame's split blobs.
void count_cut_streaks(std::vector<Blob>& blobs, std::vector<std::pair<cv::Rect, int>>& before) {
  std::vector<std::pair<cv::Rect, int>> now;
  for (Blob& blob : blobs) {
    if (blob.parts.empty()) continue;
    int area = 0, streak = 0;
    for (const auto& [box, s] : before) {
      if ((box & blob.box).area() > area) area = (box & blob.box).area(), streak = s;
    }
    blob.cut_streak = streak + 1;
    now.emplace_back(blob.box, blob.cut_streak);
  }
  before = std::move(now);
}

// Gives a split blob's pixels its own label back (a merge of tracked vehicles is taken whole).
void restore_whole(cv::Mat& labels, const Blob& blob) {
  for (const Blob& part : blob.parts) labels(part.box).setTo(blob.label, labels(part.box) == part.label);
}

double overlap(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter > 0 ? inter / (a.area() + b.area() - inter) : 0.0;
}

// A least-squares line through a track's ground points, g(f) = mean + velocity (f - mean frame):
// a vehicle keeps a near constant velocity on the road over its passage, and its ground points
// are quantised to the pixel (tens of centimetres per pixel in the distance), so a fit over every
// point predicts far better than the last two points' difference. Frames are counted from the
// first ground point (no cancellation in the sums).
struct GroundLine {
  long long first_frame = 0;
  double n = 0.0, sf = 0.0, sff = 0.0;
  Eigen::Vector2d sg = Eigen::Vector2d::Zero(), sfg = Eigen::Vector2d::Zero();

  void add(long long frame, const Eigen::Vector2d& g) {
    if (n == 0.0) first_frame = frame;
    const double f = static_cast<double>(frame - first_frame);
    n += 1.0, sf += f, sff += f * f, sg += g, sfg += f * g;
  }
  bool has_velocity() const { return n >= 2.0; }
  Eigen::Vector2d at(long long frame) const {
    const double f = static_cast<double>(frame - first_frame);
    const double var = n * sff - sf * sf;  // > 0 with two distinct frames
    const Eigen::Vector2d velocity = var > 0.0 ? Eigen::Vector2d((n * sfg - sf * sg) / var) : Eigen::Vector2d::Zero();
    return (sg + velocity * (n * f - sf)) / n;
  }
};

struct BlobTrack {
  int id = 0;
  cv::Rect2d box;          // at last_frame
  cv::Point2d velocity;    // pixels per frame, of the box's centre
  long long last_frame = 0;
  long long last_matched = 0;  // the last frame matched to a blob of its own
  int hits = 0;            // frames matched to a blob of its own
  // The road-plane motion (see predicted()): the ground points' line, and the box and foot of
  // the last matched blob with a ground point (at ground_frame).
  GroundLine ground;
  cv::Rect2d ground_box;
  cv::Point2d foot;
  long long ground_frame = 0;
};

// The track's image box at `frame`. A vehicle moves at a near constant velocity on the road, not
// in the image: under perspective an approaching vehicle speeds up and grows in the image, a
// receding one slows down and shrinks, so a constant image velocity drifts off within the
// seconds a vehicle may be hidden behind another (a car behind a bus, vehicles following each
// other in the distance). When the last matched blob had a ground point and the track a road
// velocity, the box is predicted on the road: the ground point moves along its line (GroundLine),
// the box follows its image and scales by the ratio of the depths (a vehicle's image size is
// inversely proportional to its depth). Otherwise (a new track, a silhouette cut at its foot by
// the image border) at constant image velocity.
// The road part of predicted(): the box at `frame` of a vehicle whose ground point moves along
// `line`, seen at `anchor_frame` with image box `box` and foot `foot`; nullopt when either ground
// point is not in front of the camera or the foot does not project.
std::optional<cv::Rect2d> road_box(const GroundLine& line, long long anchor_frame, const cv::Rect2d& box,
                                   const cv::Point2d& foot, long long frame, const models::Camera& camera) {
  const Eigen::Vector2d g0 = line.at(anchor_frame), g1 = line.at(frame);
  const auto& c = camera.calibration();
  const double depth0 = (c.R * Eigen::Vector3d(g0.x(), g0.y(), 0.0) + c.t).z();
  const double depth1 = (c.R * Eigen::Vector3d(g1.x(), g1.y(), 0.0) + c.t).z();
  if (!(depth0 > 0.0 && depth1 > 0.0)) return std::nullopt;
  const Eigen::Vector2d to = camera.road_to_image_points(g1).col(0);
  if (!to.allFinite()) return std::nullopt;
  const double s = depth0 / depth1;
  return cv::Rect2d(cv::Point2d(to.x(), to.y()) + s * (box.tl() - foot), cv::Size2d(s * box.width, s * box.height));
}

cv::Rect2d predicted(const BlobTrack& t, long long frame, const models::Camera& camera) {
  const cv::Rect2d by_image = t.box + t.velocity * static_cast<double>(frame - t.last_frame);
  if (!t.ground.has_velocity() || t.ground_frame != t.last_matched) return by_image;
  return road_box(t.ground, t.ground_frame, t.ground_box, t.foot, frame, camera).value_or(by_image);
}

// Whether blob b's lowest point agrees with track t's road prediction (header: foot_gate): within
// gate x the predicted box's height vertically and gate x its larger side horizontally of the image
// of the predicted ground point, plus one pixel each way (the foot's row, the mean x of that row and
// the box the prediction scales from are whole pixels: on a blob 2 px tall the gate alone would be
// finer than the grid). The road line holds after views cut by the border too (their feet are not
// ground points, but the vehicle drives on): a vehicle leaving the image has its predicted foot
// beyond the border, or behind the camera, where no blob's foot can be. True when either has no
// ground point (a new track, a silhouette cut by the border) or the gate is off.
bool foot_agrees(const BlobTrack& t, const Blob& b, const cv::Rect2d& pred, long long frame,
                 const models::Camera& camera, double gate) {
  if (gate <= 0.0 || !b.has_ground || !t.ground.has_velocity()) return true;
  const Eigen::Vector2d foot = camera.road_to_image_points(t.ground.at(frame)).col(0);
  if (!foot.allFinite()) return false;  // behind the camera
  constexpr double kPixel = 1.0;
  return std::fabs(foot.y() - b.foot.y) <= gate * pred.height + kPixel &&
         std::fabs(foot.x() - b.foot.x) <= gate * std::max(pred.width, pred.height) + kPixel;
}

// Continues track t with blob b at `frame` (the image and the road motion).
void continue_track(BlobTrack& t, const Blob& b, long long frame) {
  const cv::Rect2d box(b.box);
  if (t.hits > 0) {
    const cv::Point2d moved = (box.tl() + box.br() - t.box.tl() - t.box.br()) * 0.5 /
                              static_cast<double>(frame - t.last_frame);
    t.velocity = t.hits == 1 ? moved : 0.5 * (t.velocity + moved);
  }
  if (b.has_ground) {
    t.ground.add(frame, b.ground);
    t.ground_frame = frame;
    t.ground_box = box;
    t.foot = b.foot;
  }
  t.box = box;
  t.last_frame = frame;
  t.last_matched = frame;
  ++t.hits;
}

struct Assignment {
  std::size_t track = SIZE_MAX;  // index into the tracks
  bool merged = false;           // the blob covers two or more vehicles: no track of its own
  bool joined = false;           // its pixels also cover a small vehicle's predicted box
};

// The share of `box` (clipped to the image) whose pixels belong to component `label`.
double label_share(const cv::Mat& labels, int label, const cv::Rect2d& box) {
  const cv::Rect r = cv::Rect(box) & cv::Rect(0, 0, labels.cols, labels.rows);
  if (box.area() <= 0.0 || r.area() <= 0) return 0.0;
  return cv::countNonZero(labels(r) == label) / box.area();
}

// Whether a track's predicted box `pred` is a member of a merge in blob box `blob`: half or more
// of it inside the blob's box, and at least merge_min_share of the blob box's area.
bool merge_member(const cv::Rect2d& blob, const cv::Rect2d& pred, double merge_min_share) {
  return (blob & pred).area() >= 0.5 * pred.area() && pred.area() >= merge_min_share * blob.area();
}

// The blobs a frame's tracking takes: a split blob (find_blobs()) in its parts, unless it is a
// merge of more tracked vehicles than it has parts (a dense clump: the column cut would hand their
// tracks fragments; they coast through it, as through any merge) or it covers at most one tracked
// vehicle and has been cut in fewer than min_streak frames in a row (header: lane_split_hold).
std::vector<Blob> blobs_to_track(std::vector<Blob> blobs, const std::vector<cv::Rect2d>& pred, double merge_min_share,
                                 int min_streak, cv::Mat& labels) {
  std::vector<Blob> out;
  for (Blob& blob : blobs) {
    const auto members = std::count_if(pred.begin(), pred.end(), [&](const cv::Rect2d& r) {
      return merge_member(cv::Rect2d(blob.box), r, merge_min_share);
    });
    const bool fresh = members < 2 && blob.cut_streak < min_streak;
    if (blob.parts.empty() || fresh || members > static_cast<long>(blob.parts.size())) {
      blob.cut_whole = !blob.parts.empty();
      restore_whole(labels, blob);
      out.push_back(std::move(blob));
    } else {
      for (Blob& part : blob.parts) out.push_back(std::move(part));
    }
  }
  return out;
}

// One frame of the blob tracker (see the header). Tracks are predicted (predicted()), so
// that vehicles crossing in the image keep their identities. A blob covering half or more of the
// predicted boxes of two or more tracks, each at least merge_min_share of the blob's box, is their
// merged image: they coast (predicted box kept) and the blob goes to none. A blob whose pixels
// cover half or more of a smaller track's predicted box is joined with that vehicle: the blob
// goes to its track, the small one coasts, and the blob's outline is marked as no one cuboid's.
// Other blobs continue the track whose predicted box they overlap most (greedy in decreasing
// intersection over union, >= min_overlap) and whose predicted foot they agree with (foot_gate), or
// start one. A part of a split blob (blobs_to_track()) is one vehicle's by construction: it is
// never a merge, only matched by overlap. A blob cut but tracked whole, and a part (whose outline
// may keep some of the other vehicle's), are joined: their outlines go to the second estimator.
std::vector<Assignment> associate(std::vector<BlobTrack>& tracks, std::vector<Blob>& blobs, cv::Mat& labels,
                                  long long frame, const VehicleBlobParams& p, const models::Camera& camera,
                                  int min_streak, int& next_id) {
  std::vector<cv::Rect2d> pred;
  for (const auto& t : tracks) pred.push_back(predicted(t, frame, camera));
  blobs = blobs_to_track(std::move(blobs), pred, p.merge_min_share, min_streak, labels);
  std::vector<Assignment> out(blobs.size());
  std::vector<bool> taken(tracks.size(), false);
  for (std::size_t b = 0; b < blobs.size(); ++b) {
    const cv::Rect2d blob_box(blobs[b].box);
    std::vector<std::size_t> covered, small;
    for (std::size_t t = 0; t < tracks.size() && !blobs[b].split; ++t) {
      if (merge_member(blob_box, pred[t], p.merge_min_share)) covered.push_back(t);
      else if ((blob_box & pred[t]).area() >= 0.5 * pred[t].area() &&
               label_share(labels, blobs[b].label, pred[t]) >= 0.5) small.push_back(t);
    }
    out[b].merged = covered.size() >= 2;
    out[b].joined = !small.empty() || blobs[b].split || blobs[b].cut_whole;
    if (!out[b].merged) covered.clear();
    covered.insert(covered.end(), small.begin(), small.end());
    for (std::size_t t : covered) {
      tracks[t].box = pred[t];
      tracks[t].last_frame = frame;
      taken[t] = true;
    }
  }
  struct Pair {
    double iou;
    std::size_t blob, track;
  };
  std::vector<Pair> pairs;
  for (std::size_t b = 0; b < blobs.size(); ++b) {
    for (std::size_t t = 0; t < tracks.size() && !out[b].merged; ++t) {
      const double iou = overlap(cv::Rect2d(blobs[b].box), pred[t]);
      if (!taken[t] && iou >= p.min_overlap && foot_agrees(tracks[t], blobs[b], pred[t], frame, camera, p.foot_gate)) {
        pairs.push_back({iou, b, t});
      }
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.iou > y.iou; });
  for (const auto& pr : pairs) {
    if (out[pr.blob].track != SIZE_MAX || taken[pr.track]) continue;
    out[pr.blob].track = pr.track;
    taken[pr.track] = true;
  }
  for (std::size_t b = 0; b < blobs.size(); ++b) {
    if (out[b].merged) continue;
    if (out[b].track == SIZE_MAX) {
      BlobTrack t;
      t.id = next_id++;
      tracks.push_back(t);
      out[b].track = tracks.size() - 1;
    }
    continue_track(tracks[out[b].track], blobs[b], frame);
  }
  return out;
}

// A blob that continued or started a track, held until the estimators may have its outline: when
// every passage that could hide in it is known (HeldViews).
struct TrackView {
  long long frame = 0;
  bool joined = false;  // associate(): its pixels also cover a smaller track's predicted box
  Blob blob;
};

// A confirmed track's passage for hidden_in(): its views in frame order, the least-squares line
// through their ground points, and its first and last views with a ground point (the anchors its
// box is predicted from before and after its passage, as predicted() does from the last one).
struct Passage {
  int id = 0;
  const std::vector<TrackView>* views = nullptr;
  GroundLine line;
  const TrackView* first_anchor = nullptr;
  const TrackView* last_anchor = nullptr;
};

Passage passage_of(int id, const std::vector<TrackView>& views) {
  Passage out;
  out.id = id;
  out.views = &views;
  for (const auto& v : views) {
    if (!v.blob.has_ground) continue;
    out.line.add(v.frame, v.blob.ground);
    if (!out.first_anchor) out.first_anchor = &v;
    out.last_anchor = &v;
  }
  return out;
}

// The frames in which a passage may hide in another track's blob (hidden_in()'s window).
std::pair<double, double> hiding_window(const Passage& a, const VehicleBlobParams& p) {
  const long long first = a.views->front().frame, last = a.views->back().frame;
  const double span = p.hidden_horizon * static_cast<double>(last - first + 1);
  return {static_cast<double>(first) - span, static_cast<double>(last) + span};
}

// Whether vehicle `other`, with no blob of its own at frame k, lies in `box` then (header:
// hidden_horizon): k within horizon x its passage's length of its passage, and its road-predicted
// box at k, from its nearer anchor, inside the image, of at least min_area and half or more inside
// `box` (the share associate() asks of a merge or join).
bool hidden_in(const Passage& other, const cv::Rect2d& box, long long k, const VehicleBlobParams& p,
               const cv::Size& image, const models::Camera& camera) {
  const auto& views = *other.views;
  const long long first = views.front().frame, last = views.back().frame;
  const auto [window_start, window_end] = hiding_window(other, p);
  const auto frame = static_cast<double>(k);
  if (!other.line.has_velocity() || frame < window_start || frame > window_end) return false;
  const auto at_k = std::lower_bound(views.begin(), views.end(), k,
                                     [](const TrackView& v, long long f) { return v.frame < f; });
  if (at_k != views.end() && at_k->frame == k) return false;
  const TrackView& a = (k > last || (k >= first && k - first > last - k)) ? *other.last_anchor : *other.first_anchor;
  const auto b = road_box(other.line, a.frame, cv::Rect2d(a.blob.box), a.blob.foot, k, camera);
  if (!b || b->area() < p.min_area || b->x < 0.0 || b->y < 0.0 || b->br().x > image.width ||
      b->br().y > image.height) {
    return false;
  }
  return (box & *b).area() >= 0.5 * b->area();
}

// The (track id, frame) of every own view (not joined) of the `targets` whose blob holds another of
// the `passages` then hidden (hidden_in()): an outline of two vehicles, no one cuboid's. Both are
// confirmed tracks' complete passages (the targets among the passages). Each target's views are
// tested only against the passages whose hiding window overlaps its frames: all of them would make
// the test O(views x vehicles), hours at the end of hours of road video.
std::set<std::pair<int, long long>> hidden_views(const std::vector<const Passage*>& targets,
                                                 const std::vector<const Passage*>& passages,
                                                 const VehicleBlobParams& p, const cv::Size& image,
                                                 const models::Camera& camera) {
  std::set<std::pair<int, long long>> out;
  if (p.hidden_horizon <= 0.0) return out;
  std::vector<std::pair<double, double>> windows;
  for (const Passage* b : passages) windows.push_back(hiding_window(*b, p));
  std::vector<std::size_t> by_start(passages.size());
  std::iota(by_start.begin(), by_start.end(), std::size_t{0});
  std::sort(by_start.begin(), by_start.end(),
            [&](std::size_t i, std::size_t j) { return windows[i].first < windows[j].first; });
  std::vector<const Passage*> nearby;
  for (const Passage* a : targets) {
    core::poll_interrupt();
    const auto first = static_cast<double>(a->views->front().frame);
    const auto last = static_cast<double>(a->views->back().frame);
    nearby.clear();
    for (std::size_t i : by_start) {
      if (windows[i].first > last) break;
      if (windows[i].second >= first && passages[i]->id != a->id) nearby.push_back(passages[i]);
    }
    for (const auto& v : *a->views) {
      if (v.joined) continue;
      for (const Passage* b : nearby) {
        if (hidden_in(*b, cv::Rect2d(v.blob.box), v.frame, p, image, camera)) {
          out.emplace(a->id, v.frame);
          break;
        }
      }
    }
  }
  return out;
}

// The mean intersection over union of `views`' boxes with the boxes a vehicle moving along road
// line `line` has at their frames, seen at view `anchor` (road_box(), as predicted() coasts a
// track); 0 when the line has no velocity.
double line_overlap(const GroundLine& line, const TrackView& anchor, const std::vector<const TrackView*>& views,
                    const models::Camera& camera) {
  if (!line.has_velocity() || views.empty()) return 0.0;
  double sum = 0.0;
  for (const TrackView* v : views) {
    const auto box = road_box(line, anchor.frame, cv::Rect2d(anchor.blob.box), anchor.blob.foot, v->frame, camera);
    if (box) sum += overlap(*box, cv::Rect2d(v->blob.box));
  }
  return sum / static_cast<double>(views.size());
}

// One outline to an estimator; a blob reaching above the horizon (sky, a gantry's structure) is no
// vehicle on the road and is skipped.
void update(filters::VehicleDimensionEstimator& estimator, int id, long long frame, const Blob& blob) {
  if (blob.contour.size() < 3) return;
  Eigen::Matrix2Xd poly(2, static_cast<Eigen::Index>(blob.contour.size()));
  for (std::size_t i = 0; i < blob.contour.size(); ++i) {
    poly.col(static_cast<Eigen::Index>(i)) << blob.contour[i].x, blob.contour[i].y;
  }
  try {
    estimator.update_polygon(id, static_cast<int>(frame), poly);
  } catch (const InvalidArgument&) {
  }
}

// Every track's views until the estimators get them (header: hidden_horizon, hidden_max_passage,
// hold_views). A track's views are finalised -- each outline given to `own`, or to `joined` when
// it was joined with or holds another vehicle (associate(), hidden_views()), its estimate taken
// and its outlines released -- once every passage that could hide in them is known. Why that is
// soon after the track ends: a view of track A at frame x is tested against the confirmed passages
// B whose hiding window [f_B - h n_B, l_B + h n_B] holds x (hiding_window(); f, l the first and
// last views, n = l - f + 1 frames, h = hidden_horizon), with B's road line and anchors from its
// whole passage, and only passages of at most C frames hide (C = hidden_max_passage x the frame
// rate). An ended B is known. A running B, at frame k, has f_B >= k + 1 - C if it may still be a
// passage of at most C frames (its span so far is at most C), and a B yet to start f_B >= k + 1;
// either reaches back at most h C frames before its start. So no unknown passage reaches below
//   frontier_k = min(k + 1, the first frame of every running track of span <= C) - h C,
// and an ended track whose last view is below frontier_k can be finalised against the ended
// passages, exactly as at the end of the video (the same estimates: each vehicle's chain has its
// own random stream; hold_views = true holds every view to the end, the same answer, for the
// tests). An ended passage stays (without its outlines) while its window reaches the first frame
// of a track not finalised, or k + 1. Held at any time: the outlines of the last (1 + h) C frames
// or so, a bound set by C, not by the video's length. Without C (0) no passage's length is
// bounded -- a vehicle may stop in view, a ghost of the background stay for minutes, and the
// longest passage seen so far is no bound: on tests/test_vehicle_estimator.py's gantry stream a
// 481-frame track followed passages of at most 107 frames -- so every view is held to the end.
// An ended track also waits while a track that may continue it (predecessor(): one of at most C
// frames starting within stitch_gap of its end) runs: at most stitch_gap + C frames, within the
// bound above when h C >= stitch_gap, as with the defaults.
class HeldViews {
 public:
  HeldViews(const VehicleBlobParams& p, double fps, const cv::Size& image, filters::VehicleDimensionEstimator& own,
            filters::VehicleDimensionEstimator& joined)
      : p_(p), cap_(p.hidden_max_passage * fps), stitch_(p.stitch_gap * fps), image_(image), own_(own),
        joined_(joined) {}

  // A blob that continued or started track `id` at `frame`.
  void add(int id, long long frame, bool joined, const Blob& blob) {
    views_[id].push_back({frame, joined, blob});
    running_.insert(id);
    ++views_seen_;
    peak_ = std::max(peak_, ++held_);
  }

  // After frame k, with `tracks` the running ones: finalises what no unknown passage can reach.
  void flush(long long k, const std::vector<BlobTrack>& tracks, std::vector<filters::VehicleEstimate>& out) {
    std::set<int> alive;
    for (const auto& t : tracks) alive.insert(t.id);
    end_tracks(alive);
    if (p_.hold_views || cap_ <= 0.0) return;
    double frontier = static_cast<double>(k + 1);
    for (int id : running_) {
      if (may_hide(views_.at(id))) frontier = std::min(frontier, static_cast<double>(views_.at(id).front().frame));
    }
    finalise(frontier - p_.hidden_horizon * cap_, k + 1, out);
    release_passages(k + 1);
  }

  // The end of the video: every track has ended. `out` is sorted by id.
  void finish(std::vector<filters::VehicleEstimate>& out) {
    end_tracks({});
    finalise(std::numeric_limits<double>::infinity(), std::numeric_limits<long long>::max(), out);
    std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.vehicle_id < y.vehicle_id; });
  }

  // Whether a track row stays: a confirmed track's, not of a hidden view (as a merge's, no one
  // vehicle's box).
  bool keeps(const TrackRow& r) const {
    const int id = static_cast<int>(r.id);
    return !unconfirmed_.count(id) && !hidden_.count({vehicle_of(id), r.frame});
  }
  // The vehicle a track's rows belong to: the track it continues (predecessor()), else itself.
  int vehicle_of(int track) const {
    const auto it = continued_.find(track);
    return it == continued_.end() ? track : it->second;
  }
  std::size_t peak() const { return peak_; }
  long long views_seen() const { return views_seen_; }

 private:
  // Whether a track's views are a ghost of the background (header: min_travel): ground points in
  // two or more of them, all within min_travel metres of one another along the road.
  bool ghost(const std::vector<TrackView>& vs) const {
    const Eigen::Vector2d along = own_.camera().road_axis().head<2>();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    int grounded = 0;
    for (const auto& v : vs) {
      if (!v.blob.has_ground) continue;
      const double s = v.blob.ground.dot(along);
      lo = std::min(lo, s), hi = std::max(hi, s), ++grounded;
    }
    return grounded >= 2 && hi - lo < p_.min_travel;
  }

  // Whether a passage with these views may hide in another track's (span <= C; no C: any).
  bool may_hide(const std::vector<TrackView>& vs) const {
    return cap_ <= 0.0 || static_cast<double>(vs.back().frame - vs.front().frame + 1) <= cap_;
  }

  // The running tracks not in `alive` end: a confirmed one becomes a passage, the views of one
  // matched in fewer than confirm_frames frames (a flicker) go.
  void end_tracks(const std::set<int>& alive) {
    for (auto it = running_.begin(); it != running_.end();) {
      if (alive.count(*it)) {
        ++it;
        continue;
      }
      auto& vs = views_.at(*it);
      if (static_cast<int>(vs.size()) >= p_.confirm_frames && !ghost(vs)) {
        const Passage passage = passage_of(*it, vs);
        if (const int earlier = predecessor(passage)) {
          continue_passage(earlier, *it);
        } else {
          ended_.emplace(*it, passage);
        }
      } else {
        unconfirmed_.insert(*it);
        held_ -= vs.size();
        views_.erase(*it);
      }
      it = running_.erase(it);
    }
  }

  // The ended track, not finalised, that passage b (a track just ended) continues (header:
  // stitch_gap), or 0: one that ended at most stitch_gap before b's first view and moved along one
  // road line with it. The line is fitted to both tracks' ground points (a short track's own line
  // may rest on a few feet, one of them a merged blob's; the two together span the gap); from the
  // earlier one's last view with a ground point it must predict b's first kNearGap boxes, and from
  // b's first such view the earlier one's last kNearGap, each with a mean overlap of kMinOverlap or
  // more (line_overlap()). Of several, the one whose smaller mean is the largest.
  int predecessor(const Passage& b) const {
    constexpr std::size_t kNearGap = 5;
    constexpr double kMinOverlap = 0.5;
    if (stitch_ <= 0.0 || !may_hide(*b.views) || !b.first_anchor) return 0;
    const auto& bv = *b.views;
    const long long first = bv.front().frame;
    std::vector<const TrackView*> after;
    for (std::size_t j = 0; j < std::min(kNearGap, bv.size()); ++j) after.push_back(&bv[j]);
    int best = 0;
    double best_overlap = kMinOverlap;
    for (const auto& [id, a] : ended_) {
      const auto& av = *a.views;
      const long long last = av.back().frame;
      if (finalised_.count(id) || !a.last_anchor || last >= first || static_cast<double>(first - last) > stitch_) {
        continue;
      }
      std::vector<const TrackView*> before;
      for (std::size_t j = av.size() - std::min(kNearGap, av.size()); j < av.size(); ++j) before.push_back(&av[j]);
      GroundLine both;
      for (const auto* vs : {&av, &bv}) {
        for (const auto& v : *vs) {
          if (v.blob.has_ground) both.add(v.frame, v.blob.ground);
        }
      }
      const double agree = std::min(line_overlap(both, *a.last_anchor, after, own_.camera()),
                                    line_overlap(both, *b.first_anchor, before, own_.camera()));
      if (agree >= best_overlap) best = id, best_overlap = agree;
    }
    return best;
  }

  // Whether an ended track may still be continued (predecessor()) by a running track or one
  // starting from frame `next` on. Only a track of at most C frames continues one (a longer one has
  // stopped in view, or is a ghost), so an ended track waits at most C frames, and the answer is
  // the same when every view is held to the end.
  bool awaits_continuation(const std::vector<TrackView>& vs, long long next) const {
    if (stitch_ <= 0.0) return false;
    const long long last = vs.back().frame;
    if (static_cast<double>(next - last) <= stitch_) return true;
    return std::any_of(running_.begin(), running_.end(), [&](int id) {
      const auto& rv = views_.at(id);
      const long long first = rv.front().frame;
      return first > last && static_cast<double>(first - last) <= stitch_ && may_hide(rv);
    });
  }

  // Track `later`'s views become the ended track `earlier`'s, its passage one over both.
  void continue_passage(int earlier, int later) {
    auto& to = views_.at(earlier);
    auto& from = views_.at(later);
    to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
    views_.erase(later);
    ended_.at(earlier) = passage_of(earlier, to);  // its anchors point into the grown vector
    continued_[later] = earlier;
  }

  // Finalises the ended tracks whose last view is below `frontier` and that no track may still
  // continue (awaits_continuation(); `next`: the next frame), in order of id.
  void finalise(double frontier, long long next, std::vector<filters::VehicleEstimate>& out) {
    std::vector<const Passage*> targets, passages;
    for (const auto& [id, passage] : ended_) {
      if (may_hide(*passage.views)) passages.push_back(&passage);
      if (!finalised_.count(id) && static_cast<double>(passage.views->back().frame) < frontier &&
          !awaits_continuation(*passage.views, next)) {
        targets.push_back(&passage);
      }
    }
    if (targets.empty()) return;
    const auto hidden = hidden_views(targets, passages, p_, image_, own_.camera());
    for (const Passage* a : targets) {
      core::poll_interrupt();
      auto& vs = views_.at(a->id);
      for (auto& v : vs) {
        const bool is_hidden = hidden.count({a->id, v.frame}) > 0;
        update(v.joined || is_hidden ? joined_ : own_, a->id, v.frame, v.blob);
        if (is_hidden) hidden_.emplace(a->id, v.frame);
        std::vector<cv::Point>().swap(v.blob.contour);  // the outline is the memory; the box stays
      }
      out.push_back(vehicle(a->id, vs));
      own_.forget(a->id);
      joined_.forget(a->id);
      held_ -= vs.size();
      finalised_.insert(a->id);
    }
  }

  // The answer for a confirmed track (vehicle_answer()). first/last_frame and frames_seen count
  // every view.
  filters::VehicleEstimate vehicle(int id, const std::vector<TrackView>& vs) const {
    const auto estimate_of = [id](const filters::VehicleDimensionEstimator& est) {
      return est.next_frame(id) > 1 ? est.estimate(id) : filters::VehicleEstimate{};
    };
    filters::VehicleEstimate e =
        vehicle_answer(estimate_of(own_), [&] { return estimate_of(joined_); }, p_);
    e.vehicle_id = id;
    e.first_frame = static_cast<int>(vs.front().frame);
    e.last_frame = static_cast<int>(vs.back().frame);
    e.frames_seen = static_cast<int>(vs.size());
    return e;
  }

  // Drops the finalised passages that hide nowhere any more: longer than C, or with a hiding
  // window ending before every view still to finalise (the running and the ended unfinalised
  // tracks', and frames from `next` on).
  void release_passages(long long next) {
    long long open = next;
    for (const auto& [id, vs] : views_) {
      if (!finalised_.count(id)) open = std::min(open, vs.front().frame);
    }
    for (auto it = finalised_.begin(); it != finalised_.end();) {
      const Passage& b = ended_.at(*it);
      if (may_hide(*b.views) && hiding_window(b, p_).second >= static_cast<double>(open)) {
        ++it;
        continue;
      }
      ended_.erase(*it);
      views_.erase(*it);
      it = finalised_.erase(it);
    }
  }

  const VehicleBlobParams& p_;
  double cap_;     // C, frames (0: none)
  double stitch_;  // stitch_gap, frames (0: off)
  cv::Size image_;
  filters::VehicleDimensionEstimator& own_;
  filters::VehicleDimensionEstimator& joined_;
  std::map<int, std::vector<TrackView>> views_;  // every track's not yet released
  std::set<int> running_;                        // tracks with views still running
  std::map<int, Passage> ended_;                 // confirmed ended tracks (their views in views_)
  std::set<int> finalised_;                      // of ended_: estimated, outlines released
  std::set<int> unconfirmed_;                    // ended in fewer than confirm_frames views
  std::set<std::pair<int, long long>> hidden_;   // hidden views of finalised tracks (their rows go)
  std::map<int, int> continued_;                 // a track -> the earlier one it continues (predecessor())
  std::size_t held_ = 0, peak_ = 0;              // views with their outlines
  long long views_seen_ = 0;
};

models::Camera camera_for(const models::Camera& camera, int width, int height) {
  models::CameraCalibration c = camera.calibration();
  if (c.image_width > 0 && (c.image_width != width || c.image_height != height)) {
    throw InvalidArgument("the camera's image_size " + std::to_string(c.image_width) + "x" +
                          std::to_string(c.image_height) + " is not the video's " + std::to_string(width) + "x" +
                          std::to_string(height));
  }
  c.image_width = width;
  c.image_height = height;
  return models::Camera(c);
}

void draw(cv::Mat& frame, const Blob& blob, int id, const filters::VehicleDimensionEstimator& est) {
  const cv::Scalar colour((id * 67) % 200 + 55, (id * 131) % 200 + 55, (id * 29) % 200 + 55);
  cv::polylines(frame, std::vector<std::vector<cv::Point>>{blob.contour}, true, colour, 2);
  const auto e = est.estimate(id);
  const std::string label = std::to_string(id) + (e.valid ? " " + e.class_name + (e.heavy ? " H" : " L") : "");
  cv::putText(frame, label, blob.box.tl() + cv::Point(0, -4), cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1);
}

}  // namespace

VehiclePipelineResult measure_vehicles(const std::string& video, const models::Camera& camera,
                                       std::vector<models::VehicleModel> models, const VehiclePipelineParams& params,
                                       const std::string& render, const FrameProgress& progress) {
  validate(params);
  VideoSource source(video);
  filters::VehicleDimensionEstimator estimator(camera_for(camera, source.width(), source.height()), std::move(models),
                                               params.estimator);
  // Outlines of more than one vehicle (HeldViews) go to a second estimator, used only for a vehicle
  // with no clean view: a large vehicle with distant ones in its outline all along.
  filters::VehicleDimensionEstimator joined_views(estimator.camera(), estimator.prior().params().models,
                                                  params.estimator);
  image::KdeBackground background(params.background);
  std::unique_ptr<AtomicVideoWriter> writer;
  // The rendered video's running class: the clean outlines as they come (the estimators proper
  // see them once HeldViews finalises their tracks).
  std::unique_ptr<filters::VehicleDimensionEstimator> live;
  if (!render.empty()) {
    writer = std::make_unique<AtomicVideoWriter>(render, source.fps() > 0 ? source.fps() : 25.0,
                                                 cv::Size(source.width(), source.height()));
    live = std::make_unique<filters::VehicleDimensionEstimator>(estimator.camera(), estimator.prior().params().models,
                                                                params.estimator);
  }
  const Eigen::Matrix3d& K = estimator.camera().calibration().K;
  const VehicleBlobParams blob = blob_sizes_for(params.blobs, std::sqrt(K(0, 0) * K(1, 1)));
  const cv::Mat kernel = blob.blob_closing > 1
                             ? cv::getStructuringElement(cv::MORPH_RECT, {blob.blob_closing, blob.blob_closing})
                             : cv::Mat();
  VehiclePipelineResult result;
  std::vector<BlobTrack> tracks;
  const double fps = source.fps() > 0 ? source.fps() : 25.0;
  HeldViews views(blob, fps, cv::Size(source.width(), source.height()), estimator, joined_views);
  int next_id = 1;
  const int min_streak = std::max(1, static_cast<int>(std::lround(blob.lane_split_hold * fps)));
  std::vector<std::pair<cv::Rect, int>> cut_before;  // the last frame's split blobs (count_cut_streaks())
  cv::Mat frame, y, mask, labels;
  while (source.read(frame)) {
    core::poll_interrupt();
    const long long k = ++result.frames;
    background.apply(frame, y);
    image::foreground_mask(y, blob.foreground_threshold, mask);
    if (!kernel.empty()) cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, kernel);
    std::vector<Blob> blobs = find_blobs(mask, frame, blob, estimator.camera(), labels);
    count_cut_streaks(blobs, cut_before);
    const auto matched = associate(tracks, blobs, labels, k, blob, estimator.camera(), min_streak, next_id);
    for (std::size_t b = 0; b < blobs.size(); ++b) {
      if (matched[b].merged) continue;  // two or more vehicles in one blob: no one's silhouette
      const int id = tracks[matched[b].track].id;
      const cv::Rect& r = blobs[b].box;
      // Pixel boxes of whole pixels i0..i1: x = i0 - 0.5, w = i1 - i0 + 1 (continuous coordinates).
      result.tracks.push_back({k, static_cast<std::uint64_t>(id), static_cast<float>(r.x - 0.5),
                               static_cast<float>(r.y - 0.5), static_cast<float>(r.width),
                               static_cast<float>(r.height), 1.0});
      views.add(id, k, matched[b].joined, blobs[b]);
      if (live && !matched[b].joined) update(*live, id, k, blobs[b]);
    }
    if (writer) {
      for (std::size_t b = 0; b < blobs.size(); ++b) {
        if (matched[b].merged) continue;
        const int id = tracks[matched[b].track].id;
        if (live->next_frame(id) > 1) draw(frame, blobs[b], id, *live);
      }
      writer->write(frame);
    }
    tracks.erase(std::remove_if(tracks.begin(), tracks.end(),
                                [&](const BlobTrack& t) {
                                  const bool ended = k - t.last_frame > blob.lost_memory;
                                  if (ended && live) live->forget(t.id);
                                  return ended;
                                }),
                 tracks.end());
    views.flush(k, tracks, result.vehicles);
    if (progress) progress(k, source.expected_frame_count());
  }
  if (result.frames == 0) throw IoError("video '" + video + "' has no frames");
  // Confirmed tracks only, their rows too; a track whose blobs were always merged with another
  // vehicle's has no views and is not reported.
  views.finish(result.vehicles);
  auto& rows = result.tracks;
  rows.erase(std::remove_if(rows.begin(), rows.end(), [&](const TrackRow& r) { return !views.keeps(r); }),
             rows.end());
  for (auto& r : rows) r.id = static_cast<std::uint64_t>(views.vehicle_of(static_cast<int>(r.id)));
  result.views = views.views_seen();
  result.peak_held_views = static_cast<long long>(views.peak());
  if (writer) writer->commit();
  return result;
}

}  // namespace vtrack::apps

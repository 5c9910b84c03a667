#pragma once
// Vehicle dimensions and light/heavy classes (particle-filters-human-vehicle §3) as an
// application: the observations file, the vehicles.csv answer, and the run from observations
// shared by the CLI (`vtrack vehicles --observations`) and Python.
//
// The observations file (obs.csv): one silhouette of one vehicle per line,
//   frame,vehicle_id,x,y,w,h                  an image box [x, x + w] x [y, y + h], or
//   frame,vehicle_id,x1,y1,x2,y2,...,xn,yn    an image polygon of n >= 3 vertices,
// in pixels (continuous coordinates, pixel centres at integers; OpenCV's), frames from 1. Blank
// lines, lines starting with '#' and a first line starting with "frame" (a header) are skipped.
// A vehicle's rows must come in order of frame.
//
// vehicles.csv: a header and one row per vehicle, by id,
//   vehicle_id,class,light_heavy,W,H,L,first_frame,last_frame,frames_used
// W, H, L in metres (3 decimals), first/last_frame the frames it was seen in, frames_used the
// frames its estimate uses (filters/vehicle_dimensions.hpp: fully in view, feasible ray). A
// vehicle never fully in view has class "not_fully_in_view", light_heavy "unknown" and empty
// W, H, L: reported as such, not guessed.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vtrack/filters/vehicle_dimensions.hpp"
#include "vtrack/models/camera.hpp"

namespace vtrack::apps {

struct VehicleSilhouette {
  int frame = 0;
  int vehicle_id = 0;
  bool is_box = false;
  Eigen::Matrix2Xd points;  // the polygon (2 x n), or for a box (x, y) and (w, h) as 2 columns
};

// InvalidArgument "PATH:LINE: ..." naming the field for a malformed line (not a number, NaN, a
// frame < 1, an odd number of coordinates, fewer than 3 vertices, w or h <= 0); IoError for a
// missing or unreadable file.
std::vector<VehicleSilhouette> read_vehicle_observations(const std::string& path);

// Runs the estimator over the silhouettes in file order; a silhouette the geometry refuses (one
// crossing the horizon) is an InvalidArgument naming the vehicle and the frame.
std::vector<filters::VehicleEstimate> estimate_vehicles(filters::VehicleDimensionEstimator& estimator,
                                                        const std::vector<VehicleSilhouette>& silhouettes);

// Writes vehicles.csv (above) through write_text_atomically; `models` names the classes.
void write_vehicles_csv(const std::string& path, const std::vector<filters::VehicleEstimate>& estimates);

}  // namespace vtrack::apps

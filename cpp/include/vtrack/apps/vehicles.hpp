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

#include "vtrack/apps/config.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/pipeline.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/filters/vehicle_dimensions.hpp"
#include "vtrack/image/kde_background.hpp"
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

// ---- video -> vehicles ----------------------------------------------------------------------------
//
// The pipeline: the KDE background model (the project's; the paper's own system used an adaptive
// Gaussian mixture [7], which the KDE model of the mb-tbd paper replaces here: one background
// subtraction for every pipeline) -> its foreground mask (y < foreground_threshold), closed with a
// square of blob_closing pixels to join a vehicle's fragments -> connected components of at least
// min_area pixels as blobs, each with its outer contour (the silhouette: phase 1 measured image
// boxes 0.4-2.2 m off, outlines exact) -> a blob tracker -> the estimator per vehicle.
//
// The tracker. A vehicle on a road is one large blob that moves by a fraction of its own size per
// frame, in clutter-free foreground; the box GLMB (built for people detections with misses and
// clutter) is not needed. Each track's box is predicted on the road plane: the ground point under
// the silhouette's lowest image point (a bottom corner of the cuboid) moves along a least-squares
// line (constant velocity in metres), the box follows its image and scales by perspective; at
// constant image velocity until the track has two ground points (vehicles crossing in the image,
// or hidden behind another for seconds, keep their identities); each blob continues the track
// whose predicted box it overlaps most (intersection over union >= min_overlap, greedy in
// decreasing overlap, so the assignment is deterministic); an unmatched blob starts a track; a track unmatched for more than
// lost_memory frames ends. Occlusion: a blob covering half or more of the predicted boxes of two
// or more tracks is those vehicles merged in the image; its outline is no one cuboid's, so it goes
// to no track and no estimator, and the tracks coast on their predictions until they separate.
// Only tracks whose predicted box is at least merge_min_share of the blob's box count as members
// of a merge: a large near vehicle (a bus, a lorry leaving under a gantry) covers the small boxes
// of distant vehicles, or of tracks coasting behind it, in most of its frames; counted, they made
// its blob a "merge" in every frame, so it never got a track of its own and was never found
// (benchmarks/vehicles.py, gantry seed 300: a 13.5 m bus). Now such a blob goes to the large
// vehicle's track by overlap and, when its pixels cover half or more of a small track's
// predicted box ("joined"), the small track coasts and the outline, possibly two vehicles', goes
// to a second estimator whose answer is used only for a vehicle with no clean view.
// A blob continues a track with a road prediction only if its lowest point lies within foot_gate
// of the track's predicted box height (and of its larger side across), plus a pixel of
// quantisation, from the image of the track's predicted ground point: a vehicle's nearest bottom
// corner moves by a pixel or two per frame, so a jump of half its own image height is another
// vehicle's foot -- a blob that lost or gained a vehicle stacked with it in the image (a near car
// below a far lorry under the gantry). It then starts a track of its own instead of switching
// this one to the other vehicle and bending its road line. A ratio of the vehicle's own image
// size: the same at any resolution (benchmarks/vehicles.py: the values tried). The road line is
// the vehicle's even after its views cut by the image border (no ground point in them): a lorry
// leaving the image past a roadside camera has its predicted foot behind the camera, so the car
// entering from that border in the other direction starts its own track instead of taking the
// lorry's (whose answer it made a 5.7 m light vehicle).
// Outlines of two vehicles found afterwards: a vehicle far behind a nearer one in the same lane
// (under a gantry, on a low mast) shows above it in the image, and the two emerge from the distance
// as one blob; no track of the far one exists yet, so nothing marks the blob as two vehicles' and
// its outline, tens of frames of it, reaches the near one's estimator, and its box, scored as the
// far vehicle's, the track rows (benchmarks/vehicles.py: the missed cars and heavies called light
// of the tuning scenes). When the blob parts, the far vehicle gets a track of its own, and its
// road line says where it was before. So the estimators get the outlines at the end of the video:
// a track's view is "hidden" when another confirmed track, with no blob of its own in that frame
// and within hidden_horizon times its own passage's length (in frames) of its passage, has its
// road-predicted box (predicted() from its first or last view with a ground point, whichever is
// nearer) inside the image, at least min_area, and half or more inside the view's blob box. A
// hidden view goes to the second estimator, as a joined one, and has no track row (as a merge: no
// one vehicle's box). A ratio of the vehicles' own passages, the same at any frame rate. 0 = off
// (every view as the tracker saw it; each vehicle's estimate is then what it was when the
// estimator was fed frame by frame). Only a passage of at most hidden_max_passage seconds hides: a
// vehicle in view for minutes has stopped, or is a ghost of the background, and its road line (a
// constant velocity) says nothing of where it was before or after. Memory: a track's views
// (outlines included) are held only until every passage that could hide in them is known, soon
// after the track ends (src/apps/vehicles.cpp, HeldViews, gives the argument): the outlines of the
// last (1 + hidden_horizon) x hidden_max_passage seconds or so, whatever the video's length. With
// hidden_max_passage 0 (no limit) no bound exists and every view is held to the end of the video
// (~1 KB a view: ~300 MB per hour of busy road at 25 frames/s), as hold_views = true does with
// the limit (the same answer as streaming; for tests).
// Vehicles abreast in adjacent lanes, seen from beside the road, overlap in the image and can stay
// one blob for their whole passage (at the same speed). Such a blob is cut at an image column
// where its lower outline (the lowest pixel of each column: for one cuboid the images of its
// bottom edges, within its width across the road) leaves a gap across the road of lane_split_gap
// metres or more between two runs of columns: two lanes' vehicles. A shorter near vehicle inside
// a long far one's columns, its run between two of the far one's, is cut out of them, and a far
// part then in pieces (two far vehicles, one either side of it) is taken as its pieces
// (src/apps/vehicles.cpp, lane_cut(), gives the rules). In colour video, pixels of the near part
// above its lowest quarter whose colour is twice as likely under the far part's colours go back to
// the far part (the far vehicle's body above the near one: the binary mask cannot tell where the
// near vehicle's roof is). The parts are tracked as blobs, never as merges; their outlines may still hold some of the
// other vehicle, so they go to the second estimator as joined ones. A blob of at most one tracked
// vehicle is taken in its parts only once it has been cut in every frame for lane_split_hold
// seconds: a clump of traffic far off may show such a gap for a frame or two (gantry seed 100: a
// bus among four cars, whose track the cut broke), and cutting at once started short tracks of
// fragments (benchmarks/vehicles.py: the values tried). Until then the blob is one track's, its
// outline a joined one. A blob of two tracked vehicles is cut at once (they are known to be two).
// Vehicles abreast in the same image columns (a camera along the road) or in one lane stay one
// blob: one track, the estimator fed a two-vehicle outline (a limitation; benchmarks/vehicles.py
// counts it). A track matched in fewer than confirm_frames frames is not reported (a flicker of
// the background).
// A vehicle's track broken by a merge longer than lost_memory (a car coasting behind a bus, a
// clump that parts) is taken up by a new track when the vehicle shows again: two vehicles
// reported for one, each with part of its outlines (benchmarks/vehicles.py, Table 3: most of the
// extra vehicles). So a confirmed track that starts at most stitch_gap seconds after one ended is
// that track's continuation when one road line, fitted to both tracks' ground points and run
// across the gap from each one's view nearest it (as predicted() coasts a track), predicts the
// other's boxes next to the gap (its first or last five views) with a mean intersection over
// union of 0.5 or more; of several, the one that agrees best. Its views, rows and outlines become
// the earlier track's (src/apps/vehicles.cpp, HeldViews::predecessor()). A merged blob of two
// vehicles has a box far larger than either's, and a vehicle following in the same lane is metres
// off the line, so neither continues another vehicle's track (0.3 instead of 0.5 stitched more,
// and lost vehicles and heavies: benchmarks/vehicles.py). (The rendered video, drawn as the frames
// come, shows the later track's own id.) 0 = off.
// Nor is a track whose ground points lie within min_travel metres of one another along the road:
// a ghost of the background (road uncovered where something stood while the background was
// learnt, a patch of changed light). A vehicle enters the view moving, so even one that stops in
// view has travelled metres. In metres on the road, so the same at any resolution; a track with
// fewer than two ground points (only at the image border) is kept.
// A vehicle's answer comes from its own (clean) views; its joined ones (split parts, blobs joined
// with or hiding another vehicle) answer when it has none, and also when the own answer is no
// one road vehicle's shape: longer than max_aspect times its width. No road vehicle is: an
// articulated lorry or a bus is at most ~7 times as long as its width (EU Directive 96/53/EC:
// 16.5-18.75 m by 2.55 m), a motorbike ~3. Such an answer comes from outlines that are not the
// vehicle's alone but were not recognised as such: two vehicles one behind the other, emerging
// from the distance as one blob before either has a track (a 10.7 m truck as 0.56 x 1.86 x 19.8 m,
// light), or a grey vehicle whose lower half the background model loses on grey asphalt, so that
// its outline's lowest point is not on the road (a 13.7 m lorry as 1.27 x 1.38 x 20.1 m, light).
// The joined answer is then taken when it is one vehicle's shape; otherwise the own one stays.
// 10 leaves a margin over every real vehicle and over the estimates of real ones
// (benchmarks/vehicles.py: the values tried). 0 = off.
// Nor does an own answer that rests on thin_views (1) used view stand against a joined one of one
// vehicle's shape resting on 3 times as many views or more. One view's ray fixes two of the
// cuboid's three dimensions (§3.1: the far corner lies on the ray, a 1-D family of W-H-L); along
// the ray the answer is the class prior's. So a heavy seen whole, apart from its neighbours, in
// one frame comes out at a Table 1 truck's size (an 11.7 m truck as 2.12 x 2.91 x 7.06 m, light),
// while its lane-cut parts, nine views from different places, fix its length (1.46 x 3.53 x
// 10.43 m, heavy). A second view from elsewhere on the road fixes the third dimension: with two
// own views the joined answer was the farther from the truth in 5 of 5 vehicles, with one in 2 of
// 9 (benchmarks/vehicles.py: the values tried). 0 = off.
//
// Pixel sizes follow the camera: the closing's side and the smallest blob are given at the
// reference focal length of 900 px (a 960x540 road camera) and scale with the camera's focal
// length f (sqrt(fx fy) of K): an object at a given distance spans f / 900 times the pixels, so the
// same physical gaps are closed and the same physical specks dropped at any resolution and lens.
// Measured in benchmarks/vehicles.py (--video-scale): fixed pixel sizes lost vehicles at 0.5x.
// The closing (3 px for f = 450-1000, 5 px at f = 1200) bridges the pixels the background model
// misses inside a vehicle; a wider one also fills the few pixels between two vehicles abreast, and
// the lane cut then reads too narrow a gap between their lower outlines. None at all leaves a
// heavy in pieces on a short focal length (benchmarks/vehicles.py: the values tried).
struct VehicleBlobParams {
  double foreground_threshold = 0.5;  // y < this is foreground (y = the KDE background likelihood)
  int blob_closing = 0;               // pixels: 0 = auto (3 at f = 900, odd; above), 1 = off, else odd
  int min_area = 0;                   // pixels: 0 = auto (150 at f = 900, times (f / 900)^2)
  double min_overlap = 0.2;           // intersection over union to continue a track
  double merge_min_share = 0.2;       // a merge member's predicted box area / the blob box's (above)
  double foot_gate = 0.5;             // foot off the predicted one / predicted height (above); 0 = off
  double lane_split_gap = 0.8;        // metres across the road between two lanes' vehicles (above); 0 = off
  double lane_split_hold = 0.25;      // seconds a blob stays cut before its parts start tracks (above)
  double hidden_horizon = 1.0;        // outlines holding a hidden vehicle, x its passage (above); 0 = off
  double hidden_max_passage = 120.0;  // seconds: longer passages hide nowhere (above); 0 = no limit
  bool hold_views = false;            // true: every view held to the end of the video (above)
  int lost_memory = 5;                // frames a track may go unmatched (it coasts through merges)
  int confirm_frames = 3;             // matched frames for a track to be a vehicle
  double min_travel = 1.0;            // metres along the road a vehicle's track covers (above); 0 = off
  double stitch_gap = 2.0;            // seconds: a track continuing one that ended (above); 0 = off
  double max_aspect = 10.0;           // length / width of one vehicle's estimate (above); 0 = off
  int thin_views = 1;                 // an own answer from this many used views or fewer is thin (above); 0 = off

  static const core::ParameterTable<VehicleBlobParams>& table();
};
void validate(const VehicleBlobParams& params);
// The blob parameters with the automatic pixel sizes (0) resolved for a camera of focal length
// `focal_px` (above).
VehicleBlobParams blob_sizes_for(VehicleBlobParams params, double focal_px);
// A vehicle's answer from the estimates of its own views and of its joined ones (either may be
// invalid: no used view; above: max_aspect, thin_views). The joined one answers when the own one
// is invalid; when the own one is not one vehicle's shape (longer than max_aspect times its width)
// and the joined one is; and when the own one is thin (at most thin_views used views) and the
// joined one is one vehicle's shape resting on 3 times as many views or more. Otherwise the own
// one answers. `joined` is called only when the own answer is invalid, not one vehicle's shape or
// thin (a joined estimate refits its chain).
filters::VehicleEstimate vehicle_answer(filters::VehicleEstimate own,
                                        const std::function<filters::VehicleEstimate()>& joined,
                                        const VehicleBlobParams& params);

struct VehiclePipelineParams {
  image::KdeBackgroundParams background;
  VehicleBlobParams blobs;
  filters::VehicleEstimatorParams estimator;
};
void validate(const VehiclePipelineParams& params);
// Sets one parameter by name in whichever section has it (background, blobs, estimator; the
// names are distinct); InvalidArgument naming an unknown one.
void set_vehicle_parameter(VehiclePipelineParams& params, const std::string& name, const core::ParameterValue& value);
// Applies a config file's sections background, blobs, estimator and its top-level seed (the
// estimator's); InvalidArgument for another section.
void apply_vehicle_config(VehiclePipelineParams& params, const Config& config);
// The config sections background, blobs and estimator with the values in `params` (what
// `vtrack params --method vehicles` prints and --config reads back).
std::vector<PipelineSection> vehicle_sections(const VehiclePipelineParams& params);

struct VehiclePipelineResult {
  std::vector<filters::VehicleEstimate> vehicles;  // confirmed tracks, by id (ids from 1, in order of appearance)
  std::vector<TrackRow> tracks;                    // every vehicle's image box per frame (MOTChallenge rows)
  long long frames = 0;
  long long views = 0;            // blobs given to tracks (the views the estimators may get)
  long long peak_held_views = 0;  // the most views held at once with their outlines (hidden_max_passage)
};

// Runs the pipeline over a video file or image folder. The camera's image size, when given, must
// be the video's. IoError for an unreadable or empty video; `render` (a .avi/.mp4/.mkv or "")
// also writes the video with each vehicle's outline, id and running class.
VehiclePipelineResult measure_vehicles(const std::string& video, const models::Camera& camera,
                                       std::vector<models::VehicleModel> models, const VehiclePipelineParams& params,
                                       const std::string& render = {}, const FrameProgress& progress = {});

}  // namespace vtrack::apps

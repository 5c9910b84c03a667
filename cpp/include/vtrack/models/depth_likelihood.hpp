#pragma once
// The depth-intensity likelihood of rgbd-glmb-switching-observation.txt (eq. 4) and the Kinect
// raw-depth conversion (eq. 3): the secondary observation of the switching model, used by the
// particle GLMB filter for tracks that a hypothesis leaves undetected.
//
// Coordinate frame (the camera frame, metres): X to the right, Y down, D along the optical axis
// (away from the camera). A person's state is eq. (7)'s [X, vX, Y, vY, D, vD]; (X, Y, D) is the
// centre of the person's bounding box in space, and eq. (2)'s detection measures exactly that
// point. The person is modelled as an upright rectangle of metric size width x height facing the
// camera at depth D, so under the pinhole camera its pixel footprint T(x) is the axis-aligned
// rectangle centred on (cx + fx X / D, cy + fy Y / D) of size (fx width / D) x (fy height / D),
// rounded to whole pixels and clipped to the image. A state with D <= min_depth (at or behind the
// camera) illuminates no pixel: T(x) is empty and its likelihood ratio is 1.
//
// Eq. (4): g2(d | x) = prod_{all pixels} varphi_i(d_i) * prod_{i in T(x)} phi_i(d_i, x) / varphi_i(d_i)
// with phi_i = N(d_i; D, sigma_t) (target) and varphi_i = N(d_i; 0, sigma_b) (no target) on a
// background-subtracted metric depth image d (background pixels 0, "obtained from the background
// subtracted image"). The paper calls sigma_t, sigma_b "variances" but writes N(.; m, sigma); here
// they are STANDARD DEVIATIONS in metres. The paper's mean depth of the target region, T-bar, is
// taken to be the state's D (the filter estimates D, so the depth the state predicts is D).
// The product over all pixels is common to every state and every hypothesis, so it cancels in the
// normalisation; only the log ratio over T(x) is computed:
//   log prod_{T(x)} phi/varphi = sum_{T(x)} [ -(d-D)^2/(2 st^2) + d^2/(2 sb^2) + log(sb/st) ]
//     = -(S2 - 2 D S1 + n D^2)/(2 st^2) + S2/(2 sb^2) + n log(sb/st),
// with S1 = sum d, S2 = sum d^2 and n = |T(x)|: O(1) per state from integral images of d and d^2.
//
// Tempering. Eq. (4) treats the hundreds to thousands of pixels of a footprint as independent
// observations. They are not (the person is one surface, the sensor noise is spatially correlated,
// the rectangle is a crude shape), so the untempered log ratio is of order 10^4 nats for a person
// at 3 m: one pixel of misalignment of a footprint edge changes it by hundreds of nats, particle
// weights degenerate to one particle, and in the GLMB the missed branch (1 - p_D) eta_depth would
// outweigh any detection by thousands of nats. We therefore raise the ratio to a power `tempering`
// (in (0, 1]; 1 = the paper's eq. 4 exactly), i.e. treat the footprint as worth tempering x n
// independent pixels. The default is chosen on vtrack.rgbd's synthetic scenario (see
// DepthLikelihoodParams); it is a modelling choice, not something the paper gives.
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/image/integral_image.hpp"

namespace vtrack::models {

// Eq. (3) constants: B, the projector-camera baseline, and W_max, the largest raw value.
constexpr double kKinectBaseline = 0.075;
constexpr double kKinectRawMax = 1084.0;
// The raw code written for "no reading" by kinect_depth_to_raw (the largest 11-bit value).
constexpr double kKinectNoReading = 2047.0;

// Eq. (3): T = 8 B F_x / (W_max - w) metres, for an 11-bit raw value w and the IR camera's
// horizontal focal length fx (pixels). Raw values >= W_max, negative or non-finite carry no
// reading and give 0 (the "no depth" value of a metric depth image).
double kinect_raw_to_depth(double raw, double fx);
// The inverse, for simulation: w = W_max - 8 B F_x / T. Depths T <= 0 or non-finite (no reading)
// and depths nearer than the sensor's minimum 8 B F_x / W_max (where w would be negative) give
// kKinectNoReading, which eq. (3) maps back to 0. Not rounded: a simulator rounds to 11 bits.
double kinect_depth_to_raw(double depth, double fx);

struct PinholeCamera {
  double fx = 525.0;  // focal lengths, pixels (Kinect v1 at 640 x 480)
  double fy = 525.0;
  double cx = 319.5;  // principal point, pixels
  double cy = 239.5;
  int width = 640;  // image size, pixels
  int height = 480;

  // A width x height camera whose unset focal length fy equals fx and whose unset principal
  // point is the image centre ((width - 1) / 2, (height - 1) / 2).
  static PinholeCamera of(int width, int height, double fx, std::optional<double> fy = {},
                          std::optional<double> cx = {}, std::optional<double> cy = {});
};

struct DepthLikelihoodParams {
  PinholeCamera camera;
  double person_width = 0.5;   // metric extent of the person's rectangle (m)
  double person_height = 1.7;
  // sigma_t = sigma_b (standard deviations, m). Why equal: the per-pixel log ratio is then
  // (2 d D - D^2) / (2 sigma^2), symmetric -- a pixel with the target's depth scores +D^2/(2 s^2),
  // a background pixel (d = 0) -D^2/(2 s^2) -- so a footprint scores positive exactly when more
  // than half its pixels look like the target, and (as |T(x)| ~ 1/D^2) the score of a person does
  // not depend on their distance. With sigma_t << sigma_b (a "realistic" target noise of 0.1-0.3
  // m) one background pixel inside T(x) -- a dropout, the feet removed by background subtraction,
  // a footprint one pixel too wide -- costs D^2/(2 sigma_t^2), hundreds of nats, and kills a
  // correctly placed track. The price of equal sigmas: D is only loosely constrained (a pixel
  // with any depth above D/2 votes for the state), so a track bridging a burst drifts in D more
  // than in X, Y, and a nearer person occluding a tracked one supports it.
  double sigma_target = 1.0;
  double sigma_background = 1.0;
  // Exponent on the eq. (4) ratio (see above). 3e-4 ~ "about 1 in 3000 footprint pixels is an
  // independent observation". Measured on the scenario's depth images (3 seeds x 3 frames, 10/50/90
  // percentiles): a person's true footprint scores +3.9 / +7.0 / +7.3 nats (untempered median
  // 23000: the product over ~3000 pixels), enough to outweigh log(1 - p_D) = -3 so a tracked
  // person survives a burst of missed detections; an empty person-sized footprint scores
  // -8.9 / -8.6 / -4.7, so a track that lost its person dies; a 10 cm sideways error costs
  // -2.9 / -2.4 / -0.2. The missed branch, log(1 - p_D) + ~7, stays at or below a detection's
  // log(p_D g / kappa) (~ +7), so detections are still preferred when present (the switching
  // model never multiplies the detected branch by g2). Chosen on vtrack.rgbd.make_rgbd_scene with
  // benchmarks/rgbd_switching.py (5 seeds, medians; detection-only particle GLMB: OSPA 0.263,
  // OSPA2 0.907, burst coverage 0.10, cardinality error 0.71, label switches / fragmentations
  // 72 / 57 in total):
  //   sigma_t, sigma_b  tempering  OSPA   OSPA2  burst cov.  card. err.  switches / frags (total)
  //   1, 1              1e-4       0.248  0.891  0.18        0.66        84 / 60
  //   1, 1              2e-4       0.189  0.844  0.46        0.46        86 / 75
  //   1, 1              3e-4       0.180  0.861  0.63        0.40        90 / 86
  //   1, 1              5e-4       0.183  0.882  0.64        0.43        107 / 90
  //   0.5, 1            2e-4       0.247  0.943  0.21        0.68        152 / 123
  //   0.3, 1            1e-4, 3e-4 0.30   0.96   0.05        0.81-0.85   156-178 / 145-172
  // (measured with births scored without depth; the default, births with depth, differs little).
  double tempering = 3e-4;
  double min_depth = 0.1;  // states nearer than this (m) have an empty footprint

  // The tunable names: person_width, person_height, sigma_target, sigma_background, tempering,
  // min_depth (the camera is the model's geometry, given with it).
  static const core::ParameterTable<DepthLikelihoodParams>& table();
};

// InvalidArgument naming the parameter (or the camera's field) and its value.
void validate(const DepthLikelihoodParams& params);

// A region of the image known to be covered by a surface at some depth (the footprint of a
// detected person, or of a tracked one): a target farther than `hides_beyond` is hidden there, so
// those pixels of its T(x) say nothing about it (see DepthLikelihood::log_ratio).
struct Occluder {
  image::Rect rect;
  double hides_beyond = 0.0;  // metres: states with D > hides_beyond are occluded by rect
  // A reported track's footprint rather than a detection's: it hides only the states of viewers
  // that are not reported tracks themselves (log_ratio's viewer_reported false).
  bool tracked = false;
};

// The two integral images eq. (4) needs for one depth image: of d and of d^2; and the occluders
// of this scan (none unless the caller adds them).
struct DepthFrame {
  image::IntegralImage sum;
  image::IntegralImage sum_squares;
  std::vector<Occluder> occluders;
};

class DepthLikelihood {
 public:
  explicit DepthLikelihood(DepthLikelihoodParams params);
  const DepthLikelihoodParams& params() const { return params_; }

  // Checks a background-subtracted metric depth image (single-channel float32 or float64, the
  // camera's width x height, finite, >= 0) and builds its integral images.
  DepthFrame frame(const cv::Mat& depth) const;
  // T(x) for a position (X, Y, D), clipped to the image (empty when D <= min_depth).
  image::Rect footprint(double X, double Y, double D) const;
  // Tempered log ratio tempering * log prod_{T(x)} phi/varphi for each column (X, Y, D) of a
  // 3 x n matrix of positions, written to out (size n). O(1) per state (and per occluder).
  // Occlusion: the pixels of T(x) inside an occluder of the frame that hides the state (D >
  // hides_beyond) are left out of the product -- the target is behind a nearer surface there, so
  // it predicts nothing about those pixels (their phi/varphi ratio is 1). Overlapping occluders
  // are not de-duplicated: the removed count is clamped to |T(x)| (and S1, S2 to >= 0).
  // visible (optional, resized to n): the fraction of T(x) that no occluder hides (1 for an
  // empty footprint). viewer_reported: the positions are a reported track's, which the
  // footprints of tracks (Occluder::tracked) do not hide.
  void log_ratio(const DepthFrame& frame, const Eigen::Ref<const Eigen::Matrix3Xd>& positions,
                 Eigen::Ref<Eigen::VectorXd> out, Eigen::VectorXd* visible = nullptr,
                 bool viewer_reported = false) const;

 private:
  DepthLikelihoodParams params_;
};

}  // namespace vtrack::models

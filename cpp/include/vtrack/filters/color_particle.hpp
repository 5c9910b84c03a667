#pragma once
// Single-object colour-histogram particle filters initialised with a box (part-based-graphical-
// model-pf.txt): the conventional colour particle filter it compares against (sections 2-3.2,
// after Nummiaro, Koller-Meier & Van Gool 2003) and its part-based particle filter on a graphical
// model with message particles (sections 3.3-4, eqs. 14-30). docs/follow.md describes both; the
// measurements behind the defaults are in benchmarks/follow.py's docstring.
//
// Boxes are (x, y, w, h): top-left corner and size in pixels, continuous. Particle states are the
// paper's X = (cx, cy, h, w) (section 3.2) with the previous frame's X for the second-order
// auto-regressive dynamics of eq. 13 (models::BoxMotion): 8 components, one particle per row.
// Frames are 8-bit BGR (CV_8UC3); every update must get a frame of the size init saw.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "vtrack/core/parameters.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/image/color_histogram.hpp"
#include "vtrack/models/box_motion.hpp"
#include "vtrack/smc/blocks.hpp"
#include "vtrack/smc/particle_set.hpp"
#include "vtrack/smc/sir.hpp"

namespace vtrack::filters {

struct Box {
  double x = 0.0, y = 0.0, w = 0.0, h = 0.0;
};

// What both filters share: the likelihood, the dynamics, the histogram, the template.
struct ColorTrackingParams {
  // sigma of the colour likelihood (eqs. 11 and 24):
  //   p(z | x) = exp(-(1 - rho) / (2 sigma^2)) / (sqrt(2 pi) sigma).
  // The text gives sigma^2 = 0.2 for eq. 11, eq. 24's normaliser reads sigma = 0.2; sigma = 0.2
  // tracks better (benchmarks/follow.py: phase 1 with the NumPy filter and this filter's own rows),
  // so it is the default.
  double sigma = 0.2;
  // Eq. 13's noise and the size guard (models/box_motion.hpp).
  models::BoxMotionParams motion;
  // The 16 x 4 x 4 HSV histogram of section 3.1 (image/color_histogram.hpp), weighted by
  // Nummiaro et al.'s kernel (section 3.1's "color histograms of positional information"; its
  // ref. [14] weights so): it tracks better on PETS09 (benchmarks/follow.py).
  image::ColorHistogramParams histogram{16, 4, 4, true};
  // Slow template update (off by default; Nummiaro et al. section 4.1):
  //   q <- (1 - template_update) q + template_update p(estimate's box),
  // made only in frames where the estimate's Bhattacharyya coefficient is at least
  // occlusion_threshold, so an occluder does not leak into the template. In [0, 1].
  double template_update = 0.0;
  // A target (colour PF) or part (part-based PF) is judged occluded when the largest
  // Bhattacharyya coefficient (eq. 10) among its predicted particles is below this; in [0, 1].
  double occlusion_threshold = 0.75;
  // update() reports the target lost (ok = false) when the largest coefficient among the
  // predicted particles (every part's, for the part-based PF) is below this, in [0, 1]: on
  // PETS09-S2L1's segments a tracked person never scored below 0.5 (1% quantile 0.59), the
  // background of the synthetic occlusion scene 0.15-0.18 once the figure had left the image.
  double lost_threshold = 0.3;

  static const core::ParameterTable<ColorTrackingParams>& table();
};
void validate(const ColorTrackingParams& params);

// The conventional colour particle filter (sections 2-3.2).
struct ColorParticleParams {
  int n_particles = 30;  // N (section 5: 30 for the conventional method)
  // Selective resampling (Step 3): resample when N_eff (eq. 7) <= ess_threshold N; in [0, 1].
  double ess_threshold = 0.5;
  core::ResamplingScheme resampling = core::ResamplingScheme::Systematic;
  std::uint64_t seed = 0;
  ColorTrackingParams color;

  static const core::ParameterTable<ColorParticleParams>& table();
};
void validate(const ColorParticleParams& params);

// How a message particle x_ba (eq. 25) is weighted.
enum class MessageWeight {
  // eq. 26: the sending node's own weight pi_b (how well b sees itself at x_b).
  neighbour,
  // eq. 20: the receiving node's likelihood p(z_a | x_a = x_ba) (its template at the message box).
  target,
  // eq. 19: the product of the two (p(z_a | x_ba) p(x_ba | z_b)).
  product,
};
const std::vector<std::pair<std::string, MessageWeight>>& message_weight_names();

// The part-based particle filter (sections 3.3-4).
struct PartParticleParams {
  // Number of parts when no layout is given: horizontal stripes of equal height (2: the upper
  // and lower halves of a person, the paper's sequences 1-2; 3: a face, its sequence 3), every
  // pair connected. In [1, 16].
  int parts = 2;
  int n_particles = 15;  // N per node (section 5: 15 per node and message for two nodes)
  // The joint draw of Step 5 (eqs. 27-30 are multinomial: one uniform per draw).
  core::ResamplingScheme resampling = core::ResamplingScheme::Multinomial;
  MessageWeight message_weight = MessageWeight::neighbour;
  std::uint64_t seed = 0;
  ColorTrackingParams color;

  static const core::ParameterTable<PartParticleParams>& table();
};
void validate(const PartParticleParams& params);

// The graph: each part a box given as fractions (fx, fy, fw, fh) of the object's box (the part's
// box is (x + fx w, y + fy h, fw w, fh h)), and undirected edges between parts.
struct PartLayout {
  std::vector<std::array<double, 4>> parts;
  std::vector<std::pair<int, int>> edges;
  // n stripes of equal height, every pair of parts connected.
  static PartLayout stripes(int n);
};
// InvalidArgument for no parts, a fraction that is not finite, a part of zero size, an edge to a
// part that does not exist, a self-loop or a repeated edge.
void validate(const PartLayout& layout);

// Message geometry of eq. 21, x_ba = A_ba x_b + b_ba on X = (cx, cy, h, w), from the boxes of
// nodes b and a at initialisation, following b's scale: a's centre keeps its offset from b's
// centre in units of b's size, a's size its ratio to b's size. Then A_ba has the diagonal
// (1, 1, h_a0 / h_b0, w_a0 / w_b0) and the entries A(0, 3) = (cx_a0 - cx_b0) / w_b0 and
// A(1, 2) = (cy_a0 - cy_b0) / h_b0, and b_ba = 0.
struct MessageMap {
  Eigen::Matrix4d A = Eigen::Matrix4d::Identity();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  static MessageMap between(const Box& from, const Box& to);
  // Applied to both halves of n states (n x 8) into out (n x 8).
  void apply(const Eigen::MatrixXd& states, Eigen::MatrixXd& out) const;
};

// The colour likelihood of one template at a block of box states, for the SMC engine's
// observation concept (smc/model.hpp). It scores against the frame of a shared FrameContext,
// which the filter points at the current frame before each step (the engine passes only a
// vector measurement), and leaves the coefficients there.
struct FrameContext {
  const cv::Mat* frame = nullptr;
  image::HsvBinImage bins;
  std::optional<image::ColorModel> model;
  std::vector<double> boxes;  // scratch: n x 4 (x, y, w, h)
  double max_rho = 0.0;       // largest coefficient scored since it was reset
};
class ColorLikelihood {
 public:
  ColorLikelihood(std::shared_ptr<FrameContext> context, double sigma)
      : context_(std::move(context)), sigma_(sigma) {}
  int min_state_dim() const { return 4; }
  void check(const Eigen::VectorXd& z) const;
  void log_likelihood(const models::StatesView<double>& x, const Eigen::VectorXd& z,
                      double* out) const;

 private:
  std::shared_ptr<FrameContext> context_;
  double sigma_;
};

class ColorParticleFilter {
 public:
  explicit ColorParticleFilter(const ColorParticleParams& params = {});

  // Template from `box` of `frame`; particles all at the box, zero velocity. InvalidArgument for
  // a box of non-positive or non-finite size, one with no pixel in the frame or only black ones.
  void init(const cv::Mat& frame, const Box& box);
  // Steps 2-4; returns ok: false when the estimate's centre is outside the frame or the largest
  // coefficient is below lost_threshold (the target left the image or is lost). InvalidArgument before init, for a frame
  // of another size or type.
  bool update(const cv::Mat& frame);

  bool initialized() const { return sir_.has_value(); }
  const ColorParticleParams& params() const { return params_; }
  // The estimate of eq. 8 (the init box before the first update).
  Box box() const { return box_; }
  // The particles' boxes (N x 4, x y w h) and normalised weights after the last update (after
  // its selective resampling, if it resampled: then the weights are 1/N).
  Eigen::MatrixXd particle_boxes() const;
  Eigen::VectorXd weights() const;
  // Largest Bhattacharyya coefficient among the last update's particles, and whether it was below
  // occlusion_threshold.
  double coefficient() const { return coefficient_; }
  bool occluded() const { return coefficient_ < params_.color.occlusion_threshold; }
  const std::vector<double>& reference() const;

 private:
  using Filter = smc::Sir<models::BoxMotion, ColorLikelihood>;
  ColorParticleParams params_;
  std::shared_ptr<FrameContext> context_;
  std::optional<Filter> sir_;
  int rows_ = 0, cols_ = 0;
  Box box_;
  double coefficient_ = 1.0;
};

class PartParticleFilter {
 public:
  // An empty layout means PartLayout::stripes(params.parts).
  explicit PartParticleFilter(const PartParticleParams& params = {}, PartLayout layout = {});

  // One template per part from its box of `box`; InvalidArgument as ColorParticleFilter::init,
  // for the whole box and for every part's box.
  void init(const cv::Mat& frame, const Box& box);
  // Steps 2-6; ok as ColorParticleFilter::update.
  bool update(const cv::Mat& frame);

  bool initialized() const { return !nodes_.empty(); }
  const PartParticleParams& params() const { return params_; }
  const PartLayout& layout() const { return layout_; }
  int part_count() const { return static_cast<int>(layout_.parts.size()); }
  // The whole object's box: the mean of the object boxes each non-occluded part implies (by its
  // geometry to the object at initialisation; every part's when all are occluded).
  Box box() const { return box_; }
  // Part p's estimate (eq. 22), occlusion judgement and largest coefficient of the last update.
  Box part_box(int p) const;
  bool occluded(int p) const;
  double coefficient(int p) const;
  // Part p's weighted predicted and message particles of the last update (Step 5's set:
  // (1 + degree) N boxes, interleaved as eqs. 28-29 order them) and their normalised weights,
  // whose weighted mean is the estimate (eqs. 22-23).
  Eigen::MatrixXd particle_boxes(int p) const;
  Eigen::VectorXd weights(int p) const;
  // Part p's N particles after Step 5's draw (x-bar, N x 4 boxes), the next prediction's start.
  Eigen::MatrixXd drawn_boxes(int p) const;
  // The message map of edge (from, to) (eq. 21).
  const MessageMap& message(int from, int to) const;

 private:
  struct Incoming {
    int from;
    MessageMap map;
  };
  struct Node {
    std::vector<Incoming> incoming;
    std::optional<image::ColorModel> model;
    std::optional<models::BoxMotion> motion;  // eq. 13, size limits from the part's box
    MessageMap to_object;           // the object's box from this part's (for box())
    Eigen::MatrixXd updated;        // x-bar: N x 8, equally weighted after Step 5
    Eigen::MatrixXd predicted;      // x-hat: N x 8 (Step 2)
    Eigen::VectorXd log_weight;     // log pi-hat (Step 3, eq. 24)
    std::vector<double> rho;        // coefficients of the predicted particles
    smc::ParticleSet<double> joint; // Step 5's set of the last update
    Box box;
    double coefficient = 1.0;
    bool occluded = false;
  };
  void predict();
  void score(const cv::Mat& frame, std::vector<std::vector<Eigen::MatrixXd>>& messages,
             std::vector<std::vector<Eigen::VectorXd>>& message_log_lik);
  void draw(std::size_t a, const std::vector<Eigen::MatrixXd>& messages,
            const std::vector<Eigen::VectorXd>& message_log_lik);
  void estimate_object();
  const Node& node(int p) const;

  PartParticleParams params_;
  PartLayout layout_;
  std::vector<Node> nodes_;
  smc::BlockStreams streams_;
  core::Rng rng_;
  image::HsvBinImage bins_;
  std::vector<double> boxes_;  // scratch
  int rows_ = 0, cols_ = 0;
  Box box_;
};

// Shared checks: a CV_8UC3 frame (of rows x cols when those are positive) and an init box.
void check_frame(const cv::Mat& frame, int rows, int cols);
void check_init_box(const cv::Mat& frame, const Box& box, const char* what = "box");

}  // namespace vtrack::filters

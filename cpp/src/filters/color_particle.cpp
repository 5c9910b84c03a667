#include "vtrack/filters/color_particle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "vtrack/core/errors.hpp"

namespace vtrack::filters {

namespace {

// X = (cx, cy, h, w) -> box (x, y, w, h).
Box box_of(double cx, double cy, double h, double w) { return Box{cx - w / 2, cy - h / 2, w, h}; }

// Boxes (x, y, w, h) of n states (rows of the first 4 columns of `x`) into out (n x 4 row-major).
void boxes_of(const models::StatesView<double>& x, std::vector<double>& out) {
  const Eigen::Index n = x.rows();
  out.resize(static_cast<std::size_t>(4 * n));
  const double* cx = models::column(x, 0);
  const double* cy = models::column(x, 1);
  const double* h = models::column(x, 2);
  const double* w = models::column(x, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    double* b = out.data() + 4 * i;
    b[0] = cx[i] - w[i] / 2;
    b[1] = cy[i] - h[i] / 2;
    b[2] = w[i];
    b[3] = h[i];
  }
}

Eigen::MatrixXd boxes_matrix(const Eigen::MatrixXd& states) {
  Eigen::MatrixXd out(states.rows(), 4);
  out.col(0) = states.col(0) - states.col(3) / 2;
  out.col(1) = states.col(1) - states.col(2) / 2;
  out.col(2) = states.col(3);
  out.col(3) = states.col(2);
  return out;
}

// N copies of the state (cx, cy, h, w) of `box` with zero velocity (X_{k-1} = X_k).
Eigen::MatrixXd initial_states(const Box& box, int n) {
  Eigen::MatrixXd s(n, 8);
  const double x[4] = {box.x + box.w / 2, box.y + box.h / 2, box.h, box.w};
  for (int c = 0; c < 8; ++c) s.col(c).setConstant(x[c % 4]);
  return s;
}

// ok of update(): the estimate's centre in the frame and a coefficient of at least `lost`.
bool in_view(const Box& b, double max_rho, double lost, int cols, int rows) {
  const double cx = b.x + b.w / 2, cy = b.y + b.h / 2;
  return max_rho > 0.0 && max_rho >= lost && cx >= 0.0 && cy >= 0.0 && cx < cols && cy < rows;
}

std::string box_text(const Box& b) {
  return "(" + std::to_string(b.x) + ", " + std::to_string(b.y) + ", " + std::to_string(b.w) +
         ", " + std::to_string(b.h) + ")";
}

// Template update (ColorTrackingParams::template_update): q <- (1 - a) q + a p(box) when box's
// coefficient is at least the occlusion threshold. Returns the new model (or the old one).
image::ColorModel updated_template(const image::ColorModel& model, const cv::Mat& frame,
                                   const Box& box, const ColorTrackingParams& p,
                                   image::HsvBinImage& workspace) {
  const double b[4] = {box.x, box.y, box.w, box.h};
  double rho = 0.0;
  model.coefficients(frame, b, 1, 4, &rho, workspace);
  if (rho < p.occlusion_threshold || rho <= 0.0) return model;
  const auto seen = image::ColorModel::from_box(frame, box.x, box.y, box.w, box.h, p.histogram);
  std::vector<double> mixed(model.reference().size());
  for (std::size_t u = 0; u < mixed.size(); ++u) {
    mixed[u] = (1.0 - p.template_update) * model.reference()[u] +
               p.template_update * seen.reference()[u];
  }
  return image::ColorModel(p.histogram, mixed);
}

}  // namespace

// ---- parameters ---------------------------------------------------------------------------------

const core::ParameterTable<ColorTrackingParams>& ColorTrackingParams::table() {
  using P = ColorTrackingParams;
  static const auto t = core::ParameterTable<P>()
                            .add("sigma", &P::sigma)
                            .include(&P::motion)
                            .include(&P::histogram)
                            .add("template_update", &P::template_update)
                            .add("occlusion_threshold", &P::occlusion_threshold)
                            .add("lost_threshold", &P::lost_threshold);
  return t;
}

void validate(const ColorTrackingParams& p) {
  require(p.sigma > 0.0 && std::isfinite(p.sigma), "sigma", p.sigma, "positive and finite");
  models::validate(p.motion);
  image::validate(p.histogram);
  require(p.template_update >= 0.0 && p.template_update <= 1.0, "template_update",
          p.template_update, "in [0, 1]");
  require(p.occlusion_threshold >= 0.0 && p.occlusion_threshold <= 1.0, "occlusion_threshold",
          p.occlusion_threshold, "in [0, 1]");
  require(p.lost_threshold >= 0.0 && p.lost_threshold <= 1.0, "lost_threshold", p.lost_threshold,
          "in [0, 1]");
}

const core::ParameterTable<ColorParticleParams>& ColorParticleParams::table() {
  using P = ColorParticleParams;
  static const auto t =
      core::ParameterTable<P>()
          .add("n_particles", &P::n_particles)
          .add("ess_threshold", &P::ess_threshold)
          .add_choice("resampling", &P::resampling, core::resampling_scheme_names())
          .add("seed", &P::seed)
          .include(&P::color);
  return t;
}

void validate(const ColorParticleParams& p) {
  require(p.n_particles >= 1, "n_particles", p.n_particles, ">= 1");
  require(p.ess_threshold >= 0.0 && p.ess_threshold <= 1.0, "ess_threshold", p.ess_threshold,
          "in [0, 1]");
  validate(p.color);
}

const std::vector<std::pair<std::string, MessageWeight>>& message_weight_names() {
  static const std::vector<std::pair<std::string, MessageWeight>> names{
      {"neighbour", MessageWeight::neighbour},
      {"target", MessageWeight::target},
      {"product", MessageWeight::product}};
  return names;
}

const core::ParameterTable<PartParticleParams>& PartParticleParams::table() {
  using P = PartParticleParams;
  static const auto t =
      core::ParameterTable<P>()
          .add("parts", &P::parts)
          .add("n_particles", &P::n_particles)
          .add_choice("resampling", &P::resampling, core::resampling_scheme_names())
          .add_choice("message_weight", &P::message_weight, message_weight_names())
          .add("seed", &P::seed)
          .include(&P::color);
  return t;
}

void validate(const PartParticleParams& p) {
  require(p.parts >= 1 && p.parts <= 16, "parts", p.parts, "in [1, 16]");
  require(p.n_particles >= 1, "n_particles", p.n_particles, ">= 1");
  validate(p.color);
}

PartLayout PartLayout::stripes(int n) {
  require(n >= 1 && n <= 16, "parts", n, "in [1, 16]");
  PartLayout layout;
  for (int i = 0; i < n; ++i) {
    layout.parts.push_back({0.0, static_cast<double>(i) / n, 1.0, 1.0 / n});
    for (int j = 0; j < i; ++j) layout.edges.emplace_back(j, i);
  }
  return layout;
}

void validate(const PartLayout& layout) {
  if (layout.parts.empty()) throw InvalidArgument("parts: the layout has no part");
  for (const auto& f : layout.parts) {
    for (double v : f) require(std::isfinite(v), "parts", v, "finite fractions");
    require(f[2] > 0.0 && f[3] > 0.0, "parts", std::min(f[2], f[3]), "of positive width and height");
  }
  const int n = static_cast<int>(layout.parts.size());
  for (std::size_t e = 0; e < layout.edges.size(); ++e) {
    const auto [a, b] = layout.edges[e];
    require(a >= 0 && a < n && b >= 0 && b < n, "edges", a < 0 || a >= n ? a : b,
            "parts of the layout");
    require(a != b, "edges", a, "between two different parts");
    for (std::size_t f = 0; f < e; ++f) {
      const auto [c, d] = layout.edges[f];
      require(!((a == c && b == d) || (a == d && b == c)), "edges", a, "not repeated");
    }
  }
}

// ---- message geometry (eq. 21) -----------------------------------------------------------------

MessageMap MessageMap::between(const Box& from, const Box& to) {
  MessageMap m;
  m.A.setZero();
  m.A(0, 0) = 1.0;
  m.A(1, 1) = 1.0;
  m.A(0, 3) = ((to.x + to.w / 2) - (from.x + from.w / 2)) / from.w;
  m.A(1, 2) = ((to.y + to.h / 2) - (from.y + from.h / 2)) / from.h;
  m.A(2, 2) = to.h / from.h;
  m.A(3, 3) = to.w / from.w;
  return m;
}

void MessageMap::apply(const Eigen::MatrixXd& states, Eigen::MatrixXd& out) const {
  out.resize(states.rows(), 8);
  for (int half = 0; half < 2; ++half) {
    out.middleCols(4 * half, 4) = states.middleCols(4 * half, 4) * A.transpose();
    out.middleCols(4 * half, 4).rowwise() += b.transpose();
  }
}

// ---- checks ------------------------------------------------------------------------------------

void check_frame(const cv::Mat& frame, int rows, int cols) {
  if (frame.empty()) throw InvalidArgument("frame is empty");
  if (frame.type() != CV_8UC3) {
    throw InvalidArgument("frame must be 8-bit BGR (3 channels of uint8)");
  }
  if (rows > 0 && (frame.rows != rows || frame.cols != cols)) {
    throw InvalidArgument("frame is " + std::to_string(frame.cols) + "x" +
                          std::to_string(frame.rows) + ", init saw " + std::to_string(cols) +
                          "x" + std::to_string(rows));
  }
}

void check_init_box(const cv::Mat& frame, const Box& box, const char* what) {
  if (!(std::isfinite(box.x) && std::isfinite(box.y) && std::isfinite(box.w) &&
        std::isfinite(box.h))) {
    throw InvalidArgument(std::string(what) + " must be finite, got " + box_text(box));
  }
  if (!(box.w > 0.0 && box.h > 0.0)) {
    throw InvalidArgument(std::string(what) + " must have positive width and height, got " +
                          box_text(box));
  }
  const image::Rect r = image::pixel_rect(box.x, box.y, box.w, box.h);
  const int x0 = std::max(0, r.x), y0 = std::max(0, r.y);
  const int x1 = std::min(frame.cols, r.x + r.width), y1 = std::min(frame.rows, r.y + r.height);
  if (x1 <= x0 || y1 <= y0) {
    throw InvalidArgument(std::string(what) + " " + box_text(box) + " has no pixel in the " +
                          std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                          " frame");
  }
  if (cv::countNonZero(frame(cv::Rect(x0, y0, x1 - x0, y1 - y0)).reshape(1)) == 0) {
    throw InvalidArgument(std::string(what) + " " + box_text(box) +
                          " is all black: its colour histogram holds nothing to track");
  }
}

// ---- the colour likelihood (eq. 11) ------------------------------------------------------------

void ColorLikelihood::check(const Eigen::VectorXd&) const {
  if (!context_ || !context_->frame || !context_->model) {
    throw InvalidArgument("the colour likelihood has no frame or template");
  }
}

void ColorLikelihood::log_likelihood(const models::StatesView<double>& x, const Eigen::VectorXd&,
                                     double* out) const {
  FrameContext& c = *context_;
  boxes_of(x, c.boxes);
  const auto n = static_cast<std::size_t>(x.rows());
  c.model->coefficients(*c.frame, c.boxes.data(), n, 4, out, c.bins);  // eq. 10
  for (std::size_t i = 0; i < n; ++i) c.max_rho = std::max(c.max_rho, out[i]);
  image::color_log_likelihood(out, n, sigma_, out);  // eq. 11, in place
}

// ---- the conventional colour PF ----------------------------------------------------------------

ColorParticleFilter::ColorParticleFilter(const ColorParticleParams& params)
    : params_(params), context_(std::make_shared<FrameContext>()) {
  validate(params_);
  context_->bins = image::HsvBinImage(params_.color.histogram);
}

void ColorParticleFilter::init(const cv::Mat& frame, const Box& box) {
  check_frame(frame, 0, 0);
  check_init_box(frame, box);
  context_->model = image::ColorModel::from_box(frame, box.x, box.y, box.w, box.h,
                                                params_.color.histogram);
  smc::SirParams sir;
  sir.n_particles = params_.n_particles;
  sir.resampling = params_.resampling;
  sir.ess_threshold = params_.ess_threshold;
  sir.seed = params_.seed;
  sir.threads = 1;  // the likelihood shares one frame workspace
  sir_.reset();
  sir_.emplace(models::BoxMotion(params_.color.motion, box.h, box.w),
               ColorLikelihood(context_, params_.color.sigma),
               initial_states(box, params_.n_particles), sir);
  rows_ = frame.rows;
  cols_ = frame.cols;
  box_ = box;
  coefficient_ = 1.0;
}

bool ColorParticleFilter::update(const cv::Mat& frame) {
  if (!sir_) throw InvalidArgument("update before init");
  check_frame(frame, rows_, cols_);
  context_->frame = &frame;
  context_->max_rho = 0.0;
  const Eigen::VectorXd& m = sir_->step(Eigen::VectorXd());  // Steps 2-4, eqs. 5-8, 13
  context_->frame = nullptr;
  box_ = box_of(m[0], m[1], m[2], m[3]);
  coefficient_ = context_->max_rho;
  const bool ok = in_view(box_, coefficient_, params_.color.lost_threshold, cols_, rows_);
  if (ok && params_.color.template_update > 0.0) {
    context_->model = updated_template(*context_->model, frame, box_, params_.color,
                                       context_->bins);
  }
  return ok;
}

Eigen::MatrixXd ColorParticleFilter::particle_boxes() const {
  if (!sir_) throw InvalidArgument("particles before init");
  return boxes_matrix(sir_->particles().states());
}

Eigen::VectorXd ColorParticleFilter::weights() const {
  if (!sir_) throw InvalidArgument("weights before init");
  return sir_->particles().weights();
}

const std::vector<double>& ColorParticleFilter::reference() const {
  if (!context_->model) throw InvalidArgument("template before init");
  return context_->model->reference();
}

// ---- the part-based PF (sections 3.3-4) --------------------------------------------------------

PartParticleFilter::PartParticleFilter(const PartParticleParams& params, PartLayout layout)
    : params_(params),
      layout_(layout.parts.empty() ? PartLayout::stripes(params.parts) : std::move(layout)),
      streams_(params.seed, 1),
      rng_(params.seed, 0),
      bins_(params.color.histogram) {
  validate(params_);
  validate(layout_);
}

void PartParticleFilter::init(const cv::Mat& frame, const Box& box) {
  check_frame(frame, 0, 0);
  check_init_box(frame, box);
  const std::size_t n_parts = layout_.parts.size();
  std::vector<Box> part_boxes(n_parts);
  for (std::size_t p = 0; p < n_parts; ++p) {
    const auto& f = layout_.parts[p];
    part_boxes[p] = Box{box.x + f[0] * box.w, box.y + f[1] * box.h, f[2] * box.w, f[3] * box.h};
    check_init_box(frame, part_boxes[p], "part box");
  }
  // Step 1: the graph, each node's template and updated particle set.
  std::vector<Node> nodes(n_parts);
  for (std::size_t p = 0; p < n_parts; ++p) {
    Node& node = nodes[p];
    const Box& b = part_boxes[p];
    node.model = image::ColorModel::from_box(frame, b.x, b.y, b.w, b.h, params_.color.histogram);
    node.motion.emplace(params_.color.motion, b.h, b.w);  // size limits from the part's own box
    node.to_object = MessageMap::between(b, box);
    node.updated = initial_states(b, params_.n_particles);
    node.box = b;
  }
  for (const auto& [a, b] : layout_.edges) {
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    nodes[ub].incoming.push_back({a, MessageMap::between(part_boxes[ua], part_boxes[ub])});
    nodes[ua].incoming.push_back({b, MessageMap::between(part_boxes[ub], part_boxes[ua])});
  }
  nodes_ = std::move(nodes);
  rows_ = frame.rows;
  cols_ = frame.cols;
  box_ = box;
}

// Step 2: x-hat = eq. 13 applied to x-bar, each node's noise from its own blocks of streams_.
void PartParticleFilter::predict() {
  const Eigen::Index n = params_.n_particles;
  const Eigen::Index blocks = smc::block_count(n);
  streams_.reserve(blocks * static_cast<Eigen::Index>(nodes_.size()));
  Eigen::MatrixXd eps(n, 4);
  std::vector<float> normals;
  for (std::size_t p = 0; p < nodes_.size(); ++p) {
    for (Eigen::Index b = 0; b < blocks; ++b) {
      const smc::BlockRange r = smc::block_range(b, n);
      normals.resize(static_cast<std::size_t>(4 * r.size()));
      streams_[static_cast<Eigen::Index>(p) * blocks + b].fill_normal(normals.data(),
                                                                     normals.size());
      for (int k = 0; k < 4; ++k) {
        for (Eigen::Index i = 0; i < r.size(); ++i) {
          eps(r.begin + i, k) = normals[static_cast<std::size_t>(k * r.size() + i)];
        }
      }
    }
    Node& node = nodes_[p];
    node.predicted.resize(n, 8);
    node.motion->propagate(models::StatesView<double>(node.updated),
                           models::StatesView<double>(eps), node.predicted);
  }
}

// Step 3 (eq. 24) for every node, and Step 4's message particles (eq. 25) with, when the message
// weight needs it, the receiving node's likelihood at them (eq. 20). One colour conversion: the
// region holding every box scored.
void PartParticleFilter::score(const cv::Mat& frame,
                               std::vector<std::vector<Eigen::MatrixXd>>& messages,
                               std::vector<std::vector<Eigen::VectorXd>>& message_log_lik) {
  const Eigen::Index n = params_.n_particles;
  const bool score_messages = params_.message_weight != MessageWeight::neighbour;
  messages.assign(nodes_.size(), {});
  message_log_lik.assign(nodes_.size(), {});
  // Every box to score, row-major (x, y, w, h): the predicted particles node by node, then the
  // messages node by node, edge by edge.
  std::vector<Eigen::MatrixXd> blocks;
  for (const Node& node : nodes_) blocks.push_back(boxes_matrix(node.predicted));
  for (std::size_t a = 0; a < nodes_.size(); ++a) {
    for (const Incoming& in : nodes_[a].incoming) {
      messages[a].emplace_back();
      in.map.apply(nodes_[static_cast<std::size_t>(in.from)].predicted, messages[a].back());
      if (score_messages) blocks.push_back(boxes_matrix(messages[a].back()));
    }
  }
  boxes_.clear();
  for (const Eigen::MatrixXd& m : blocks) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      for (int c = 0; c < 4; ++c) boxes_.push_back(m(i, c));
    }
  }
  const std::size_t count = boxes_.size() / 4;
  bins_.assign(frame, image::boxes_roi(boxes_.data(), count, 4, frame.cols, frame.rows));
  std::vector<double> rho(static_cast<std::size_t>(n));
  const double sigma = params_.color.sigma;
  const double* at = boxes_.data();
  auto next_scores = [&](const Node& node, Eigen::VectorXd& log_lik) {
    node.model->coefficients(bins_, at, static_cast<std::size_t>(n), 4, rho.data());  // eq. 10
    at += 4 * n;
    log_lik.resize(n);
    image::color_log_likelihood(rho.data(), rho.size(), sigma, log_lik.data());  // eq. 24
  };
  for (Node& node : nodes_) {
    next_scores(node, node.log_weight);
    node.rho = rho;
    node.coefficient = *std::max_element(rho.begin(), rho.end());
    node.occluded = node.coefficient < params_.color.occlusion_threshold;
  }
  if (!score_messages) return;
  for (std::size_t a = 0; a < nodes_.size(); ++a) {
    for (std::size_t l = 0; l < nodes_[a].incoming.size(); ++l) {
      message_log_lik[a].emplace_back();
      next_scores(nodes_[a], message_log_lik[a].back());
    }
  }
}

// Steps 5-6 for node a: the predicted and message particles with their weights in the order of
// eqs. 27-29 (particle i of the node, then particle i of each incoming message), their weighted
// mean (eq. 22 with the normalisation of eq. 23) and N draws by the cumulative weights (eq. 30).
// An occluded node with a visible neighbour drops its own particles (weight 0), so its estimate
// and its next particles are the ones its neighbours infer.
void PartParticleFilter::draw(std::size_t a, const std::vector<Eigen::MatrixXd>& messages,
                              const std::vector<Eigen::VectorXd>& message_log_lik) {
  Node& node = nodes_[a];
  const Eigen::Index n = params_.n_particles;
  const auto degree = static_cast<Eigen::Index>(node.incoming.size());
  bool gate = false;
  if (node.occluded) {
    for (const Incoming& in : node.incoming) {
      gate = gate || !nodes_[static_cast<std::size_t>(in.from)].occluded;
    }
  }
  Eigen::MatrixXd states((degree + 1) * n, 8);
  Eigen::VectorXd log_w((degree + 1) * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index row = (degree + 1) * i;
    states.row(row) = node.predicted.row(i);
    log_w[row] = gate ? -std::numeric_limits<double>::infinity() : node.log_weight[i];  // eq. 28
    for (Eigen::Index l = 0; l < degree; ++l) {
      const auto ul = static_cast<std::size_t>(l);
      states.row(row + 1 + l) = messages[ul].row(i);
      const Node& from = nodes_[static_cast<std::size_t>(node.incoming[ul].from)];
      double w = 0.0;  // eq. 29 with the message weight of eq. 26, 20 or 19
      switch (params_.message_weight) {
        case MessageWeight::neighbour: w = from.log_weight[i]; break;
        case MessageWeight::target: w = message_log_lik[ul][i]; break;
        case MessageWeight::product: w = from.log_weight[i] + message_log_lik[ul][i]; break;
      }
      log_w[row + 1 + l] = w;
    }
  }
  node.joint = smc::ParticleSet<double>(std::move(states), log_w);  // normalised: eqs. 23, 30
  const Eigen::VectorXd m = node.joint.mean();                          // eq. 22
  node.box = box_of(m[0], m[1], m[2], m[3]);
  node.joint.draw_ancestors(params_.resampling, n, rng_);  // Step 5's N draws
  smc::gather_rows(node.joint.states(), node.joint.ancestors().data(), n, node.updated);
}

void PartParticleFilter::estimate_object() {
  bool any_visible = false;
  for (const Node& node : nodes_) any_visible = any_visible || !node.occluded;
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  int count = 0;
  for (const Node& node : nodes_) {
    if (any_visible && node.occluded) continue;
    const Box& b = node.box;
    const Eigen::Vector4d x(b.x + b.w / 2, b.y + b.h / 2, b.h, b.w);
    sum += node.to_object.A * x + node.to_object.b;
    ++count;
  }
  sum /= count;
  box_ = box_of(sum[0], sum[1], sum[2], sum[3]);
}

bool PartParticleFilter::update(const cv::Mat& frame) {
  if (nodes_.empty()) throw InvalidArgument("update before init");
  check_frame(frame, rows_, cols_);
  predict();
  std::vector<std::vector<Eigen::MatrixXd>> messages;
  std::vector<std::vector<Eigen::VectorXd>> message_log_lik;
  score(frame, messages, message_log_lik);
  for (std::size_t a = 0; a < nodes_.size(); ++a) draw(a, messages[a], message_log_lik[a]);
  estimate_object();
  double best = 0.0;
  for (const Node& node : nodes_) best = std::max(best, node.coefficient);
  const bool ok = in_view(box_, best, params_.color.lost_threshold, cols_, rows_);
  if (ok && params_.color.template_update > 0.0) {
    for (Node& node : nodes_) {
      if (!node.occluded && in_view(node.box, node.coefficient, 0.0, cols_, rows_)) {
        node.model = updated_template(*node.model, frame, node.box, params_.color, bins_);
      }
    }
  }
  return ok;
}

const PartParticleFilter::Node& PartParticleFilter::node(int p) const {
  if (nodes_.empty()) throw InvalidArgument("parts before init");
  if (p < 0 || p >= part_count()) {
    throw InvalidArgument("part " + std::to_string(p) + " out of range [0, " +
                          std::to_string(part_count()) + ")");
  }
  return nodes_[static_cast<std::size_t>(p)];
}

Box PartParticleFilter::part_box(int p) const { return node(p).box; }
bool PartParticleFilter::occluded(int p) const { return node(p).occluded; }
double PartParticleFilter::coefficient(int p) const { return node(p).coefficient; }

Eigen::MatrixXd PartParticleFilter::particle_boxes(int p) const {
  const Node& nd = node(p);
  if (nd.joint.size() == 0) return boxes_matrix(nd.updated);
  return boxes_matrix(nd.joint.states());
}

Eigen::VectorXd PartParticleFilter::weights(int p) const {
  const Node& nd = node(p);
  if (nd.joint.size() == 0) {
    return Eigen::VectorXd::Constant(nd.updated.rows(), 1.0 / static_cast<double>(nd.updated.rows()));
  }
  return nd.joint.weights();
}

Eigen::MatrixXd PartParticleFilter::drawn_boxes(int p) const { return boxes_matrix(node(p).updated); }

const MessageMap& PartParticleFilter::message(int from, int to) const {
  for (const Incoming& in : node(to).incoming) {
    if (in.from == from) return in.map;
  }
  throw InvalidArgument("no edge from part " + std::to_string(from) + " to part " +
                        std::to_string(to));
}

}  // namespace vtrack::filters

#pragma once
// The second-order auto-regressive model of part-based-graphical-model-pf eq. 13 on an image box,
// X_k = 2 X_{k-1} - X_{k-2} + U_{k-1}, X = (cx, cy, h, w) (section 3.2: the rectangle's centre,
// height and width), with noise U whose standard deviation scales with the box.
//
// Why not models::SecondOrderAutoRegressive (the same eq. 13 with a fixed U ~ N(0, diag(sigma^2))):
// it fits (x, y, h, w) and its state [X_k, X_{k-1}] is this model's, but a fixed U in pixels is
// wrong for boxes of different sizes (a 2 px step is a tenth of a far person's width and a
// hundredth of a near one's), and eq. 13 makes the size's velocity a random walk, so with any
// size noise the box size drifts: a normalised colour histogram barely penalises a box that grows
// over the background or shrinks inside the object (the NumPy filter of benchmarks/follow.py with
// U = (3, 2, 1, 0.5) px reached h = 1046 px). So here
//   U = (noise[0] w, noise[1] h, noise[2] h, noise[3] w) * eps,  eps ~ N(0, I_4),
// with (h, w) the particle's previous box, and the new size is kept within
// [min_scale, max_scale] times a reference size (the initial box's) and at least min_size pixels:
// a guard against the drift, which the paper does not need over its 100-frame clips. The copied
// half X_{k-1} is not clamped (it is the previous state).
//
// State layout (8 components, the SMC engine's one particle per row): [cx, cy, h, w, cx', cy',
// h', w'] with ' the previous frame's. It satisfies the engine's motion concept (smc/model.hpp).
#include <array>

#include "vtrack/core/parameters.hpp"
#include "vtrack/models/states.hpp"

namespace vtrack::models {

struct BoxMotionParams {
  // Standard deviation of U (eq. 13) per component (cx, cy, h, w), as fractions of the previous
  // box's (w, h, h, w). The paper gives no value; benchmarks/follow.py's docstring has the
  // measurements behind these (a person's box of 32 x 80 px: 2.6 px and 2.4 px steps, 0.16 px
  // and 0.06 px size steps).
  std::array<double, 4> noise{0.08, 0.03, 0.002, 0.002};
  // The size (h, w) stays within [min_scale, max_scale] times the reference size.
  double min_scale = 0.8;
  double max_scale = 1.25;
  // ... and at least this many pixels per side.
  double min_size = 2.0;

  static const core::ParameterTable<BoxMotionParams>& table();
};
void validate(const BoxMotionParams& params);

class BoxMotion {
 public:
  // reference_h, reference_w: the size the scale limits refer to (positive, finite).
  BoxMotion(const BoxMotionParams& params, double reference_h, double reference_w);

  int dim() const { return 8; }
  int noise_dim() const { return 4; }
  const BoxMotionParams& params() const { return params_; }

  // next = eq. 13 for a block of particles (n x 8 states, n x 4 standard normals); next must not
  // alias prev.
  void propagate(const StatesView<double>& prev, const StatesView<double>& eps,
                 MutableStatesView<double> next) const;

 private:
  BoxMotionParams params_;
  double h_lo_, h_hi_, w_lo_, w_hi_;  // size limits in pixels
};

}  // namespace vtrack::models

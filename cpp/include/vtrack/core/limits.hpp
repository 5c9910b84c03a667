#pragma once
// Documented upper bounds on sizes and counts that users give. Each is far beyond any real use
// and far below what would overflow a narrowing conversion or exhaust memory before a useful
// error could be given: a value beyond one is rejected with InvalidArgument naming it, instead of
// ending in std::bad_alloc, an integer wrap or a job that never finishes.
#include <cstdint>
#include <string>

#include "vtrack/core/errors.hpp"

namespace vtrack::core {

// Image width or height in pixels (OpenCV's sizes are ints; no camera gives 2^20 px).
constexpr int kMaxImageSide = 1 << 20;

// Particles per track or component (n_particles, min/max_particles, birth_particles): a million
// is 1000x the papers' counts and already costs tens of MB and tens of ms per track and step.
constexpr int kMaxParticles = 1000000;

// GLMB hypotheses requested or kept per step (hypothesis_budget, max_hypotheses): the papers use
// 10^3-10^4; 10^5 ranked assignments already take seconds per step.
constexpr int kMaxHypotheses = 100000;

// Pixel coordinates and sizes of a detection box, in absolute value: no image is a billion
// pixels wide, and beyond this float rows and 3-decimal text lose the box.
constexpr double kMaxCoordinate = 1e9;

// Frame numbers of detection files and last_frame (exactly representable as doubles, and far
// from the overflow of any frame arithmetic).
constexpr long long kMaxFrame = 1000000000000000LL;  // 10^15

// InvalidArgument "<name> must be in [1, 1048576], got <value>" for an image side out of range:
// the one check of image sizes from the CLI (--image-size), Python (image_size) and files.
inline void require_image_side(long long value, const std::string& name) {
  if (value < 1 || value > kMaxImageSide) {
    throw InvalidArgument(name + " must be in [1, " + std::to_string(kMaxImageSide) + "], got " +
                          std::to_string(value));
  }
}

}  // namespace vtrack::core

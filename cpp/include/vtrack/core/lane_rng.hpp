#pragma once
// Vectorised random draws for particle loops: xoshiro256** run as kLanes interleaved streams.
//
// Why: a particle filter spends most of its time drawing normals. core::Rng::fill_normal draws
// them one 64-bit output at a time (the xoshiro state update is a serial dependence chain) and
// calls libm's log, cos and sin, which do not vectorise: about 10 ns per normal. Here kLanes
// independent xoshiro256** states sit side by side (structure of arrays), so one loop over the
// lanes advances all of them with AVX2 instructions (the multiplications by 5 and 9 become shifts
// and adds), and Box-Muller uses core::vmath's vectorisable log and sine/cosine polynomials:
// about 1 ns per normal (benchmarks/particle_filter.py's docstring has the figures).
//
// Each lane is a jump of a core::Rng (2^128 draws apart), so lanes never overlap, and a
// LaneRng's output is defined bit-for-bit by the Rng it was made from.
#include <cstddef>
#include <cstdint>

#include "vtrack/core/random.hpp"

namespace vtrack::core {

class LaneRng {
 public:
  static constexpr int kLanes = 8;

  // Lane l starts where `streams` is after l jumps; `streams` is left jumped kLanes times, so
  // LaneRngs made one after another from the same Rng draw from disjoint streams.
  explicit LaneRng(Rng& streams) noexcept;

  // n uniform doubles on [0, 1) with 52 random bits each.
  void fill_uniform(double* out, std::size_t n) noexcept;
  // n standard normals by Box-Muller: per pair, 52 bits for the radius (|z| <= 8.5) and 52 bits
  // plus 2 for the angle. Pairs land kLanes apart: out[j] and out[j + kLanes] share a radius.
  void fill_normal(double* out, std::size_t n) noexcept;
  // n standard normals in single precision, about twice as fast: 64 random bits per pair, 31 for
  // the radius (so |z| <= 6.55; the tail beyond has probability 5e-10) and 24 plus 2 for the
  // angle, float arithmetic (relative error < 1e-6). For the process noise of particle filters,
  // where this precision is far below the Monte Carlo error.
  void fill_normal(float* out, std::size_t n) noexcept;

 private:
  // kLanes fresh 64-bit outputs, one per lane.
  void next(std::uint64_t* out) noexcept;

  alignas(64) std::uint64_t s_[4][kLanes];
};

}  // namespace vtrack::core

#pragma once
// The seeded random engine of vtrack: xoshiro256** (Blackman & Vigna, 2018).
//
// Why this generator: 256 bits of state, a period of 2^256 - 1, passes BigCrush, four adds/xors
// per draw, and a jump() that advances the state by 2^128 draws, which gives provably
// non-overlapping streams from one seed. Results are defined bit-for-bit by the seed (no
// dependence on std::uniform_real_distribution, whose output differs between standard libraries),
// so the same seed gives the same tracks on every platform we ship.
#include <array>
#include <cstddef>
#include <cstdint>

namespace vtrack::core {

class Rng {
 public:
  using result_type = std::uint64_t;

  // `stream` selects one of 2^128 non-overlapping sub-sequences of the generator seeded with
  // `seed` (the state is jumped `stream` times; cost O(stream), about 1 µs per jump, polling
  // core::poll_interrupt() every 4096 jumps).
  explicit Rng(std::uint64_t seed = 0, std::uint64_t stream = 0);
  // An engine with exactly this 256-bit state (not all zero), for checking against the reference
  // implementation.
  static Rng from_state(const std::array<std::uint64_t, 4>& state);
  // The 256-bit state (for generators that run several xoshiro streams side by side, LaneRng).
  std::array<std::uint64_t, 4> state() const { return {s_[0], s_[1], s_[2], s_[3]}; }

  // Raw 64-bit output; also makes Rng a UniformRandomBitGenerator for <algorithm>.
  std::uint64_t next() noexcept;
  std::uint64_t operator()() noexcept { return next(); }
  static constexpr std::uint64_t min() { return 0; }
  static constexpr std::uint64_t max() { return ~std::uint64_t{0}; }

  // Uniform on [0, 1) with 53 random bits.
  double uniform() noexcept;
  // Uniform on [lo, hi).
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }
  // Uniform integer on [0, n), n > 0, without modulo bias (Lemire's method).
  std::uint64_t below(std::uint64_t n) noexcept;
  // Standard normal N(0, 1) by the Box-Muller transform; draws come in pairs, the second is kept.
  double normal() noexcept;

  // Batched draws: the loops are branch-free so the compiler can vectorise the transcendental
  // parts (Box-Muller on pairs); use these in particle loops rather than one call per particle.
  void fill_uniform(double* out, std::size_t n) noexcept;
  void fill_normal(double* out, std::size_t n) noexcept;
  void fill_normal(float* out, std::size_t n) noexcept;

  // Advances the state by 2^128 draws.
  void jump() noexcept;

 private:
  std::uint64_t s_[4];
  double cached_normal_ = 0.0;
  bool has_cached_normal_ = false;
};

}  // namespace vtrack::core

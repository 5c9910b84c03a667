#include "vtrack/core/random.hpp"

#include <algorithm>
#include <cmath>

#include "vtrack/core/errors.hpp"
#include "vtrack/core/interrupt.hpp"

namespace vtrack::core {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// 128-bit product for Lemire's bounded draw (a GCC/Clang extension on every platform we ship).
__extension__ using uint128 = unsigned __int128;

std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }

// SplitMix64 expands a 64-bit seed into the 256-bit state, as the xoshiro authors recommend;
// it never yields the all-zero state that xoshiro must avoid.
std::uint64_t splitmix64(std::uint64_t& x) noexcept {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// 53 high bits -> [0, 1).
inline double to_unit(std::uint64_t bits) noexcept {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t x = seed;
  for (auto& word : s_) word = splitmix64(x);
  for (std::uint64_t i = 0; i < stream; ++i) {
    if ((i & 4095) == 0) poll_interrupt();  // O(stream): a large stream takes a while
    jump();
  }
}

Rng Rng::from_state(const std::array<std::uint64_t, 4>& state) {
  if ((state[0] | state[1] | state[2] | state[3]) == 0) {
    throw InvalidArgument("xoshiro256** state must not be all zero");
  }
  Rng rng;
  for (int i = 0; i < 4; ++i) rng.s_[i] = state[i];
  return rng;
}

std::uint64_t Rng::next() noexcept {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng::uniform() noexcept { return to_unit(next()); }

std::uint64_t Rng::below(std::uint64_t n) noexcept {
  // Lemire (2019), "Fast random integer generation in an interval".
  uint128 m = static_cast<uint128>(next()) * n;
  auto low = static_cast<std::uint64_t>(m);
  if (low < n) {
    const std::uint64_t threshold = (0 - n) % n;
    while (low < threshold) {
      m = static_cast<uint128>(next()) * n;
      low = static_cast<std::uint64_t>(m);
    }
  }
  return static_cast<std::uint64_t>(m >> 64);
}

double Rng::normal() noexcept {
  if (has_cached_normal_) {
    has_cached_normal_ = false;
    return cached_normal_;
  }
  // 1 - u lies in (0, 1], so the logarithm is finite.
  const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform()));
  const double angle = kTwoPi * uniform();
  cached_normal_ = radius * std::sin(angle);
  has_cached_normal_ = true;
  return radius * std::cos(angle);
}

void Rng::fill_uniform(double* out, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) out[i] = uniform();
}

namespace {

// Box-Muller over a block: first the raw bits (sequential, cheap), then the transcendental part
// in a loop with no dependence between iterations.
template <typename T>
void fill_normal_impl(Rng& rng, T* out, std::size_t n) noexcept {
  constexpr std::size_t kBlock = 256;
  double u1[kBlock / 2];
  double u2[kBlock / 2];
  std::size_t done = 0;
  while (done < n) {
    const std::size_t pairs = std::min(kBlock / 2, (n - done + 1) / 2);
    for (std::size_t j = 0; j < pairs; ++j) {
      u1[j] = 1.0 - to_unit(rng.next());
      u2[j] = to_unit(rng.next());
    }
    double z[kBlock];
    for (std::size_t j = 0; j < pairs; ++j) {
      const double radius = std::sqrt(-2.0 * std::log(u1[j]));
      z[2 * j] = radius * std::cos(kTwoPi * u2[j]);
      z[2 * j + 1] = radius * std::sin(kTwoPi * u2[j]);
    }
    const std::size_t take = std::min(2 * pairs, n - done);
    for (std::size_t j = 0; j < take; ++j) out[done + j] = static_cast<T>(z[j]);
    done += take;
  }
}

}  // namespace

void Rng::fill_normal(double* out, std::size_t n) noexcept { fill_normal_impl(*this, out, n); }
void Rng::fill_normal(float* out, std::size_t n) noexcept { fill_normal_impl(*this, out, n); }

void Rng::jump() noexcept {
  static constexpr std::uint64_t kJump[] = {0x180ec6d33cfd0abaULL, 0xd5a61266f0c9392cULL,
                                            0xa9582618e03fc9aaULL, 0x39abdc4529b1661cULL};
  std::uint64_t t[4] = {0, 0, 0, 0};
  for (std::uint64_t word : kJump) {
    for (int b = 0; b < 64; ++b) {
      if (word & (std::uint64_t{1} << b)) {
        for (int i = 0; i < 4; ++i) t[i] ^= s_[i];
      }
      next();
    }
  }
  for (int i = 0; i < 4; ++i) s_[i] = t[i];
  has_cached_normal_ = false;
}

}  // namespace vtrack::core

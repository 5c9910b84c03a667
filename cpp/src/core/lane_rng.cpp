#include "vtrack/core/lane_rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "vtrack/core/vmath.hpp"

namespace vtrack::core {
namespace {

constexpr int L = LaneRng::kLanes;

inline std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }

// The top 52 bits of a 64-bit draw as an exact double in [0, 2^52) (via the exponent field, as
// AVX2 has no uint64 -> double conversion).
inline double top52(std::uint64_t bits) noexcept {
  return vmath::from_bits(0x4330000000000000ULL | (bits >> 12)) - 0x1.0p52;
}

// Box-Muller on one pair of draws: radius sqrt(-2 log u), u in (0, 1] from `a`; the angle is a
// quarter turn chosen by the two low bits of `b` plus phi uniform on [-pi/4, pi/4) from its top 52
// bits (so sine and cosine need only the reduced-range polynomials).
inline void box_muller(std::uint64_t a, std::uint64_t b, double& z0, double& z1) noexcept {
  const double u = (top52(a) + 1.0) * 0x1.0p-52;
  const double radius = std::sqrt(-2.0 * vmath::log(u));
  const double phi = (top52(b) * 0x1.0p-52 - 0.5) * (0.5 * vmath::kPi);
  double s, c;
  vmath::sincos_reduced(phi, s, c);
  // Rotation by a quarter turn q = b & 3: (c, s) -> (-s, c) for odd q, negated for q >= 2.
  const bool odd = (b & 1) != 0;
  const bool negate = (b & 2) != 0;
  double x = odd ? -s : c;
  double y = odd ? c : s;
  x = negate ? -x : x;
  y = negate ? -y : y;
  z0 = radius * x;
  z1 = radius * y;
}

// Box-Muller in single precision from two 32-bit draws: `ru` gives the radius, `ra` the quarter
// turn (its 2 low bits) and phi (its top 24 bits), as in box_muller above.
inline void box_muller(std::uint32_t ru, std::uint32_t ra, float& z0, float& z1) noexcept {
  // u in (0, 1]: 31 bits (signed int32 -> float is the conversion AVX2 has).
  const float u = static_cast<float>(static_cast<std::int32_t>(ru >> 1) + 1) * 0x1.0p-31f;
  const float radius = std::sqrt(-2.0f * vmath::log(u));
  const float phi = (static_cast<float>(static_cast<std::int32_t>(ra >> 8)) * 0x1.0p-24f - 0.5f) *
                    static_cast<float>(0.5 * vmath::kPi);
  float s, c;
  vmath::sincos_reduced(phi, s, c);
  const bool odd = (ra & 1u) != 0;
  const bool negate = (ra & 2u) != 0;
  float x = odd ? -s : c;
  float y = odd ? c : s;
  x = negate ? -x : x;
  y = negate ? -y : y;
  z0 = radius * x;
  z1 = radius * y;
}

}  // namespace

LaneRng::LaneRng(Rng& streams) noexcept {
  for (int l = 0; l < L; ++l) {
    const auto state = streams.state();
    for (int k = 0; k < 4; ++k) s_[k][l] = state[k];
    streams.jump();
  }
}

void LaneRng::next(std::uint64_t* out) noexcept {
  // xoshiro256** (Blackman & Vigna 2018), one step of every lane; the loop vectorises.
  for (int l = 0; l < L; ++l) {
    const std::uint64_t result = rotl(s_[1][l] * 5, 7) * 9;
    const std::uint64_t t = s_[1][l] << 17;
    s_[2][l] ^= s_[0][l];
    s_[3][l] ^= s_[1][l];
    s_[1][l] ^= s_[2][l];
    s_[0][l] ^= s_[3][l];
    s_[2][l] ^= t;
    s_[3][l] = rotl(s_[3][l], 45);
    out[l] = result;
  }
}

void LaneRng::fill_uniform(double* out, std::size_t n) noexcept {
  alignas(64) std::uint64_t bits[L];
  std::size_t done = 0;
  while (done < n) {
    next(bits);
    const std::size_t take = std::min<std::size_t>(L, n - done);
    for (std::size_t l = 0; l < take; ++l) out[done + l] = top52(bits[l]) * 0x1.0p-52;
    done += take;
  }
}

void LaneRng::fill_normal(double* out, std::size_t n) noexcept {
  alignas(64) std::uint64_t a[L];
  alignas(64) std::uint64_t b[L];
  alignas(64) double tail[2 * L];
  std::size_t done = 0;
  while (done < n) {
    next(a);
    next(b);
    // Full chunks of 2 kLanes normals go straight to `out`; the last partial one via `tail`.
    double* dst = n - done >= 2 * L ? out + done : tail;
    for (int l = 0; l < L; ++l) box_muller(a[l], b[l], dst[l], dst[l + L]);
    const std::size_t take = std::min<std::size_t>(2 * L, n - done);
    if (dst == tail) std::copy(tail, tail + take, out + done);
    done += take;
  }
}

void LaneRng::fill_normal(float* out, std::size_t n) noexcept {
  // One call of next() gives the radii of 2 kLanes pairs (its outputs read as 32-bit halves,
  // which needs no shuffling), a second their angles: 4 kLanes normals per chunk.
  alignas(64) std::uint64_t a[L];
  alignas(64) std::uint64_t b[L];
  alignas(64) std::uint32_t ra[2 * L];
  alignas(64) std::uint32_t rb[2 * L];
  alignas(64) float tail[4 * L];
  std::size_t done = 0;
  while (done < n) {
    next(a);
    next(b);
    std::memcpy(ra, a, sizeof ra);
    std::memcpy(rb, b, sizeof rb);
    float* dst = n - done >= 4 * L ? out + done : tail;
    for (int k = 0; k < 2 * L; ++k) box_muller(ra[k], rb[k], dst[k], dst[k + 2 * L]);
    const std::size_t take = std::min<std::size_t>(4 * L, n - done);
    if (dst == tail) std::copy(tail, tail + take, out + done);
    done += take;
  }
}

}  // namespace vtrack::core

#pragma once
// Vectorisable elementary functions for particle loops: exp, log, atan2 and the sine/cosine pair
// of a random angle, written branch-free (selects, not branches; exponent arithmetic on the bit
// patterns, no float-to-integer conversion) so that GCC and Clang turn a loop calling them into
// SIMD code with -O3 (-march=native: 4 doubles per AVX2 instruction). std::exp, std::log and
// std::atan2 are calls into libm that no compiler vectorises without -ffast-math; measured on the
// machine of benchmarks/particle_filter.py (AMD EPYC, AVX2) they cost 5-20 ns each, these 0.5-1.5 ns.
//
// Accuracy: within 2 ulp of the correctly rounded result on their stated domains (tested against
// libm in cpp/tests/test_vmath.cpp); they are not bit-identical to libm. sqrt needs no helper:
// std::sqrt is an exact IEEE operation and vectorises as it is, because vtrack compiles with
// -fno-math-errno.
//
// References: the polynomials are fdlibm's (Sun Microsystems, 1993: e_log.c, k_sin.c, k_cos.c)
// and Cephes' (S. L. Moshier, 1984-1992: logf.c, sinf.c, cosf.c), atan's is its Taylor series;
// the range reductions are the textbook ones (Cody & Waite 1980; Muller, "Elementary
// Functions", 2016).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace vtrack::core::vmath {

// Bit pattern of a double and back (memcpy compiles to nothing and vectorises).
inline std::uint64_t bits(double x) noexcept {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline double from_bits(std::uint64_t u) noexcept {
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

inline constexpr double kLn2Hi = 6.93147180369123816490e-01;  // ln 2, high 32 bits
inline constexpr double kLn2Lo = 1.90821492927058770002e-10;  // ln 2 - kLn2Hi
inline constexpr double kPi = 3.14159265358979323846;

// e^x. Results below 2^-1022 (x < -708.39) are flushed to 0 (no subnormals), above the largest
// double they are +inf; NaN gives NaN.
inline double exp(double x) noexcept {
  constexpr double kLog2e = 1.4426950408889634074;
  constexpr double kShifter = 0x1.8p52;  // adding it rounds to an integer held in the low bits
  const double xc = x < -708.0 ? -708.0 : (x > 709.0 ? 709.0 : x);
  const double k = xc * kLog2e + kShifter;  // n = round(x / ln 2), as k's low bits
  const double n = k - kShifter;
  // r = x - n ln 2 in two parts (Cody-Waite), |r| <= ln2 / 2.
  const double r = (xc - n * kLn2Hi) - n * kLn2Lo;
  // Taylor polynomial of degree 13 (remainder < 5e-18 relative on |r| <= ln 2 / 2).
  double p = 1.0 / 6227020800.0;
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^n from the exponent field: k's bit pattern is 0x4338... + n, so (bits + 1023) << 52 is the
  // biased exponent of 2^n for -1022 <= n <= 1023.
  const double scale = from_bits((bits(k) + 1023) << 52);
  const double y = p * scale;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  return x < -708.39 ? 0.0 : (x > 709.78 ? kInf : y);
}

// Natural logarithm of a positive normal double (x >= 2^-1022). Zero, negative, subnormal or NaN
// input gives an unspecified value (callers pass uniforms in (0, 1] or positive finite numbers).
inline double log(double x) noexcept {
  // x = 2^e m with m in [sqrt(1/2), sqrt(2)) (musl's reduction): adding bits(1) - bits(sqrt(1/2))
  // to x's bit pattern carries into the exponent field exactly when x's mantissa is >= sqrt(2),
  // so e and m come out without a branch.
  constexpr std::uint64_t kSqrtHalf = 0x3fe6a09e667f3bcdULL;
  const std::uint64_t t = bits(x) + (0x3ff0000000000000ULL - kSqrtHalf);
  const double f = from_bits((t & 0x000fffffffffffffULL) + kSqrtHalf) - 1.0;  // m - 1
  // e = (t >> 52) - 1023 as a double without an int64 -> double conversion (absent from AVX2).
  const double e = from_bits(0x4330000000000000ULL | (t >> 52)) - (0x1.0p52 + 1023.0);
  // fdlibm e_log.c: log(1 + f) = f - hfsq + s (hfsq + R), s = f / (2 + f), R minimax in s^2.
  constexpr double Lg1 = 6.666666666666735130e-01, Lg2 = 3.999999999940941908e-01,
                   Lg3 = 2.857142874366239149e-01, Lg4 = 2.222219843214978396e-01,
                   Lg5 = 1.818357216161805012e-01, Lg6 = 1.531383769920937332e-01,
                   Lg7 = 1.479819860511658591e-01;
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double w = z * z;
  const double t1 = w * (Lg2 + w * (Lg4 + w * Lg6));
  const double t2 = z * (Lg1 + w * (Lg3 + w * (Lg5 + w * Lg7)));
  const double R = t2 + t1;
  const double hfsq = 0.5 * f * f;
  return e * kLn2Hi - ((hfsq - (s * (hfsq + R) + e * kLn2Lo)) - f);
}

// sin and cos of |x| <= pi/4 (fdlibm k_sin.c and k_cos.c polynomials).
inline void sincos_reduced(double x, double& s, double& c) noexcept {
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double z = x * x;
  const double ps = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
  s = x + x * z * (S1 + z * ps);
  const double pc = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
  // cos x = 1 - z/2 + z pc, summed as fdlibm does for |x| <= 0.3 (within 1 ulp up to pi/4 too).
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  c = w + (((1.0 - w) - hz) + z * pc);
}

// atan2(y, x) in [-pi, pi] for finite y, x; atan2(0, 0) = 0.
inline double atan2(double y, double x) noexcept {
  // One division only (the divider is the bottleneck of vectorised code): with num <= den the
  // octant's |y|, |x|, t = num / den lies in [0, 1]; above tan(pi/12) it is mapped to
  // tan(atan(t) - pi/6) = (sqrt(3) num - den) / (sqrt(3) den + num), so the quotient, formed
  // once, lies in [-tan(pi/12), tan(pi/12)], where atan's Taylor series to t^25 is exact to
  // 2^-53 (the next term is below 0.268^27 / 27 = 1.5e-17).
  constexpr double kSqrt3 = 1.73205080756887729353;
  constexpr double kTanPi12 = 0.26794919243112270647;
  constexpr double kPi6 = 0.52359877559829887308;
  constexpr double kPi2 = 1.57079632679489661923;
  const double ax = x < 0.0 ? -x : x;
  const double ay = y < 0.0 ? -y : y;
  const bool swap = ay > ax;
  const double num = swap ? ax : ay;
  const double den = swap ? ay : ax;
  const bool high = num > kTanPi12 * den;
  const double tn = high ? kSqrt3 * num - den : num;
  const double td_raw = high ? kSqrt3 * den + num : den;
  const double td = td_raw == 0.0 ? 1.0 : td_raw;  // atan2(0, 0) = 0
  const double t = tn / td;
  const double z = t * t;
  // sum_{k=1..12} (-1)^k z^k / (2k + 1), Horner.
  double p = 1.0 / 25.0;
  p = p * z - 1.0 / 23.0;
  p = p * z + 1.0 / 21.0;
  p = p * z - 1.0 / 19.0;
  p = p * z + 1.0 / 17.0;
  p = p * z - 1.0 / 15.0;
  p = p * z + 1.0 / 13.0;
  p = p * z - 1.0 / 11.0;
  p = p * z + 1.0 / 9.0;
  p = p * z - 1.0 / 7.0;
  p = p * z + 1.0 / 5.0;
  p = p * z - 1.0 / 3.0;
  double a = t + t * z * p;
  a = high ? a + kPi6 : a;
  a = swap ? kPi2 - a : a;      // atan(1/t) = pi/2 - atan(t)
  a = x < 0.0 ? kPi - a : a;
  return y < 0.0 ? -a : a;
}

// Single precision, for random numbers whose last bits do not matter (LaneRng's normals).
inline std::uint32_t bits(float x) noexcept {
  std::uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline float float_from_bits(std::uint32_t u) noexcept {
  float x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

// e^x in single precision (Cephes expf.c: Cody-Waite reduction by n = round(x log2 e), degree-5
// polynomial on the remainder, 2^n assembled in the exponent bits; relative error < 1e-7 against
// libm). Results below 2^-126 (x < -87.33) are flushed to 0; above x = 88.37, where 2^n would need
// n = 128, they are +inf (e^88.37 = 2.5e38, the largest float 3.4e38); NaN gives NaN. For the KDE
// background's kernels and particle weights exp(t - max t), where the 1e-7 error is far below
// the modelling and Monte Carlo errors.
inline float exp(float x) noexcept {
  // -126 <= n <= 127; NaN is clamped too, so that the conversion of n to an integer is defined.
  const float xc = x > -87.33f ? (x < 88.37f ? x : 88.37f) : -87.33f;
  const float n = std::floor(xc * 1.44269504088896341f + 0.5f);
  float r = xc - n * 0.693359375f;  // x - n ln 2 in two parts (Cephes C1, C2)
  r = r + n * 2.12194440e-4f;
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * r * r + r + 1.0f;
  const float scale = float_from_bits(static_cast<std::uint32_t>(static_cast<std::int32_t>(n) + 127)
                                      << 23);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  return x < -87.33f ? 0.0f : (x > 88.37f ? kInf : (x == x ? p * scale : x));
}

// Natural logarithm of a positive normal float (Cephes logf.c polynomial, relative error
// < 2e-7); other input gives an unspecified value.
inline float log(float x) noexcept {
  constexpr std::uint32_t kSqrtHalf = 0x3f3504f3u;
  const std::uint32_t t = bits(x) + (0x3f800000u - kSqrtHalf);
  const float f = float_from_bits((t & 0x007fffffu) + kSqrtHalf) - 1.0f;  // m - 1, m in [sqrt 1/2, sqrt 2)
  const float e = static_cast<float>(static_cast<std::int32_t>(t >> 23) - 127);
  const float z = f * f;
  float p = 7.0376836292e-2f;
  p = p * f - 1.1514610310e-1f;
  p = p * f + 1.1676998740e-1f;
  p = p * f - 1.2420140846e-1f;
  p = p * f + 1.4249322787e-1f;
  p = p * f - 1.6668057665e-1f;
  p = p * f + 2.0000714765e-1f;
  p = p * f - 2.4999993993e-1f;
  p = p * f + 3.3333331174e-1f;
  const float y = f * z * p - 0.5f * z;
  return f + y + e * 0.693147180559945309f;
}

// sin and cos of |x| <= pi/4 in single precision (Cephes sinf.c/cosf.c polynomials, < 2e-7).
inline void sincos_reduced(float x, float& s, float& c) noexcept {
  const float z = x * x;
  s = x + x * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
  c = 1.0f - 0.5f * z +
      z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f + z * 2.443315711809948e-5f));
}

// atan2(y, x) in [-pi, pi] for finite float y, x (absolute error < 3e-7); atan2(0, 0) = 0. The
// double version's reduction; on [-tan(pi/12), tan(pi/12)] atan's series to t^11 is within
// 0.268^13 / 13 = 3e-9 of atan, below float's rounding.
inline float atan2(float y, float x) noexcept {
  constexpr float kSqrt3 = 1.73205080756887729353f;
  constexpr float kTanPi12 = 0.26794919243112270647f;
  constexpr float kPi6 = 0.52359877559829887308f;
  constexpr float kPi2 = 1.57079632679489661923f;
  constexpr float kPif = 3.14159265358979323846f;
  const float ax = x < 0.0f ? -x : x;
  const float ay = y < 0.0f ? -y : y;
  const bool swap = ay > ax;
  const float num = swap ? ax : ay;
  const float den = swap ? ay : ax;
  const bool high = num > kTanPi12 * den;
  const float tn = high ? kSqrt3 * num - den : num;
  const float td_raw = high ? kSqrt3 * den + num : den;
  const float td = td_raw == 0.0f ? 1.0f : td_raw;
  const float t = tn / td;
  const float z = t * t;
  float p = -1.0f / 11.0f;
  p = p * z + 1.0f / 9.0f;
  p = p * z - 1.0f / 7.0f;
  p = p * z + 1.0f / 5.0f;
  p = p * z - 1.0f / 3.0f;
  float a = t + t * z * p;
  a = high ? a + kPi6 : a;
  a = swap ? kPi2 - a : a;
  a = x < 0.0f ? kPif - a : a;
  return y < 0.0f ? -a : a;
}

}  // namespace vtrack::core::vmath

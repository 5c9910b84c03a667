// Micro-benchmarks of the SMC engine in C++: the particle-storage layout decision, the machine's
// floor for the range-bearing SIR (the normals and exponentials alone) and the SIR step split by
// stage. One thread, process CPU time, medians.
//
// Build against the library of a `make build` (same flags as the library) and run, on one line:
//   g++ -std=c++17 -O3 -march=native -fno-trapping-math -fno-math-errno -fPIC
//       -fno-semantic-interposition -Icpp/include
//       -isystem /usr/include/eigen3 -isystem /usr/include/opencv4 benchmarks/cpp/smc_micro.cpp
//       build/wheel/libvtrack.a -lopencv_core -o build/smc_micro && build/smc_micro
//
// Measured (AMD EPYC, 2 vCPUs shared with other builds, load average ~10; ns per particle):
//   layout, N = 1e5, d = 4     rows (N x d)   columns (d x N)
//     CV propagation              3.0            5.6
//     range-bearing likelihood    3.4            4.1
//     resampling gather           1.9            2.0
//     weighted mean               1.2            1.3
//   floor: 4 normals + 1 exp: 4.2 + 0.5 = 4.7 ns (double-precision normals: 10 ns)
//   SIR step, N = 1e5: ~23 ns in all (normals 4.2, propagation 2-3, likelihood 3.5, weights 3.5,
//   systematic resampling 3.5, gather 2.5)
// After fusing systematic resampling into the weight update (WeightUpdate::resample_systematic:
// no weight arrays written, no validation pass, uniform weights written lazily, the cumulative
// sum in four chains) and alternating two state buffers, same machine at load 7-14, perf record
// of the SIR step alone: N = 1e5 22-23.5 ns (was 24.7-25), N = 1e4 18.5 ns. Share of
// the 1e5 step: normals 24 % (~5.5 ns), gather of the resampled states + widening of the noise
// 16 %, exp + block sums 13.5 %, likelihood 13.4 %, propagation 12.5 % (store-bound: the new
// states go to a 3.2 MB array), resampling 11.4 % (was 14 % plus 4 % for writing the weights).
// 2026-11-25 (a Sapphire Rapids Xeon, 2 vCPUs, load average ~10 from other builds; ns per
// particle at N = 1e5):
//   the library as built before: normals (4) 2.2, exp 0.9, SIR step 11.8-13.6 (double states);
//   float states (Sir's Scalar = float, range-bearing residuals and atan2 in float): 10.0-11.2;
//   512-bit vectors for lane_rng, reweight, linear_transition and range_bearing: measured alone
//   (objects built without -fPIC) normals 2.2 -> 1.6, float step ~10 -> 8.0; but in the library
//   (-fPIC) normals went to 4.3: LaneRng::next was no longer inlined into fill_normal, as GCC may
//   not inline a function another library could interpose. With -fno-semantic-interposition:
//   normals 1.5, exp 0.9, SIR step 10.3-10.5 (double) and 8.1-8.5 (float).
// 2026-11-28 (an AMD EPYC with AVX-512, family 26; 2 vCPUs, load average 7-14 from other builds;
// ns per particle at N = 1e5): before, the float SIR step 6.0 (5.7-5.9 on the benchmark's own
// measurements, whose weights are more uneven), the double step 7.0; perf of the float step:
// resampling 24 % (its running maximum of the marks about half of that), the gather with the
// propagation 17 %, weights 16 %, normals 16 %, likelihood 11 %. Changed, in this order:
//   - the gather in one pass over the ancestors for all columns (the index read once per
//     particle), and block buffers kept per thread instead of allocated per block;
//   - the weights' exponentials in single precision for float states (vmath::exp(float));
//   - the gather of ancestors within a window by AVX-512 permutation (smc/gather.hpp):
//     the gather row below, by column 1.05, one pass 0.90, gather_block 0.49;
//   - the running maximum of the marks in AVX-512 registers (reweight.cpp): measured on its own
//     with systematic resampling of weights exp(-s x^2 / 2), x ~ N(0, 1), at ESS / N 0.87, 0.42,
//     0.14 and 0.05: scalar 1.29, 1.25, 1.28, 1.08, vectorised 0.55, 0.55, 0.56, 0.56. (Writing
//     each particle's index into four slots, overwritten by later particles, was as fast at ESS
//     0.87 but took 1.9 at ESS 0.14: a branch for the longer runs mispredicts.)
//   After: the float step 4.5 (4.7-4.8 on the benchmark's measurements), the double step 6.4
//   (memory-bound: its 3.2 MB state arrays leave the 1 MB L2 cache; propagation alone 1.2).
// Tried and dropped: prefetching the gather's ancestors (no gain: they are sorted and the
// hardware prefetcher follows them); splitting LaneRng's 64-bit draws into 32-bit halves by
// shifts instead of memcpy (1.2-1.4 ns per normal instead of 0.98, same output).
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vtrack/core/lane_rng.hpp"
#include "vtrack/core/random.hpp"
#include "vtrack/core/resampling.hpp"
#include "vtrack/core/vmath.hpp"
#include "vtrack/models/motion.hpp"
#include "vtrack/models/range_bearing.hpp"
#include "vtrack/smc/particle_set.hpp"
#include "vtrack/smc/sir.hpp"

using namespace vtrack;

namespace {

template <class F>
double ns_per(F f, double count, int repeats = 21) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t start = std::clock();
    f();
    t.push_back(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC * 1e9 / count);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

using Rows = Eigen::Matrix<double, Eigen::Dynamic, 4>;  // one particle per row (the engine's)
using Cols = Eigen::Matrix<double, 4, Eigen::Dynamic>;  // one particle per column

// Constant velocity, T = 1, per-axis noise factor [[a, 0], [b, c]].
constexpr double kA = 0.288, kB = 0.433, kC = 0.25;

__attribute__((noinline)) void propagate_rows(const Rows& x, const Rows& e, Rows& y) {
  const Eigen::Index n = x.rows();
  const double *px = x.col(0).data(), *vx = x.col(1).data(), *py = x.col(2).data(),
               *vy = x.col(3).data();
  const double *e0 = e.col(0).data(), *e1 = e.col(1).data(), *e2 = e.col(2).data(),
               *e3 = e.col(3).data();
  double *o0 = y.col(0).data(), *o1 = y.col(1).data(), *o2 = y.col(2).data(), *o3 = y.col(3).data();
  for (Eigen::Index i = 0; i < n; ++i) {
    o0[i] = px[i] + vx[i] + kA * e0[i];
    o1[i] = vx[i] + kB * e0[i] + kC * e1[i];
    o2[i] = py[i] + vy[i] + kA * e2[i];
    o3[i] = vy[i] + kB * e2[i] + kC * e3[i];
  }
}

__attribute__((noinline)) void propagate_cols(const Cols& x, const Cols& e, Cols& y) {
  const Eigen::Index n = x.cols();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* xi = x.data() + 4 * i;
    const double* ei = e.data() + 4 * i;
    double* yi = y.data() + 4 * i;
    yi[0] = xi[0] + xi[1] + kA * ei[0];
    yi[1] = xi[1] + kB * ei[0] + kC * ei[1];
    yi[2] = xi[2] + xi[3] + kA * ei[2];
    yi[3] = xi[3] + kB * ei[2] + kC * ei[3];
  }
}

inline double range_bearing(double px, double py, double zr, double c, double s) {
  const double dr = std::sqrt(px * px + py * py) - zr;
  const double db = core::vmath::atan2(c * py - s * px, c * px + s * py) * 100.0;
  return -0.5 * (dr * dr + db * db);
}

__attribute__((noinline)) void likelihood_rows(const Rows& x, double* out) {
  const double c = std::cos(0.46), s = std::sin(0.46);
  const double *px = x.col(0).data(), *py = x.col(2).data();
  for (Eigen::Index i = 0; i < x.rows(); ++i) out[i] = range_bearing(px[i], py[i], 134.0, c, s);
}

__attribute__((noinline)) void likelihood_cols(const Cols& x, double* out) {
  const double c = std::cos(0.46), s = std::sin(0.46);
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    out[i] = range_bearing(x(0, i), x(2, i), 134.0, c, s);
  }
}

void layout(Eigen::Index n) {
  const Rows xr = Rows::Random(n, 4) * 100.0, er = Rows::Random(n, 4);
  Rows yr(n, 4);
  const Cols xc = xr.transpose(), ec = er.transpose();
  Cols yc(4, n);
  std::vector<double> out(static_cast<std::size_t>(n));
  Eigen::VectorXd w = Eigen::VectorXd::Random(n).cwiseAbs();
  core::Rng rng(1);
  const auto ancestors = core::resample(core::ResamplingScheme::Systematic, w, n, rng);
  const double d = static_cast<double>(n);
  std::printf("layout, N = %ld: ns per particle, rows | columns\n", static_cast<long>(n));
  std::printf("  CV propagation            %5.2f | %5.2f\n",
              ns_per([&] { propagate_rows(xr, er, yr); }, d), ns_per([&] { propagate_cols(xc, ec, yc); }, d));
  std::printf("  range-bearing likelihood  %5.2f | %5.2f\n",
              ns_per([&] { likelihood_rows(xr, out.data()); }, d),
              ns_per([&] { likelihood_cols(xc, out.data()); }, d));
  std::printf("  resampling gather         %5.2f | %5.2f\n",
              ns_per([&] { smc::gather_rows(xr, ancestors.data(), n, yr, 1); }, d),
              ns_per([&] {
                for (Eigen::Index j = 0; j < n; ++j) yc.col(j) = xc.col(ancestors[static_cast<std::size_t>(j)]);
              }, d));
  std::printf("  weighted mean             %5.2f | %5.2f\n",
              ns_per([&] { volatile double m = (xr.transpose() * w)(0); (void)m; }, d),
              ns_per([&] { volatile double m = (xc * w)(0); (void)m; }, d));
}

// The gather of 4 float columns after systematic resampling (weights exp(2 N(0, 1)), as spread as
// the range-bearing problem's): column by column, as the engine did until 2026-11-28; one pass
// over the ancestors for all columns; smc::gather_block (one pass, and the AVX-512 permutation of
// ancestors within a window).
using FloatRows = Eigen::Matrix<float, Eigen::Dynamic, 4>;
__attribute__((noinline)) void gather_by_column(const FloatRows& x, const std::int64_t* a,
                                                FloatRows& y) {
  for (Eigen::Index c = 0; c < 4; ++c) {
    const float* from = x.col(c).data();
    float* to = y.col(c).data();
    for (Eigen::Index j = 0; j < x.rows(); ++j) to[j] = from[a[j]];
  }
}
__attribute__((noinline)) void gather_one_pass(const FloatRows& x, const std::int64_t* a,
                                               FloatRows& y) {
  const float *x0 = x.col(0).data(), *x1 = x.col(1).data(), *x2 = x.col(2).data(),
              *x3 = x.col(3).data();
  float *y0 = y.col(0).data(), *y1 = y.col(1).data(), *y2 = y.col(2).data(), *y3 = y.col(3).data();
  for (Eigen::Index j = 0; j < x.rows(); ++j) {
    const std::int64_t k = a[j];
    y0[j] = x0[k];
    y1[j] = x1[k];
    y2[j] = x2[k];
    y3[j] = x3[k];
  }
}

void gather(Eigen::Index n) {
  const FloatRows x = FloatRows::Random(n, 4);
  FloatRows y(n, 4);
  core::Rng rng(2);
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w[i] = std::exp(2.0 * rng.normal());
  w /= w.sum();
  const auto a = core::resample(core::ResamplingScheme::Systematic, w, n, rng);
  const double d = static_cast<double>(n);
  std::printf("\ngather of 4 float columns, N = %ld, ns per particle: by column %.2f, one pass "
              "%.2f, gather_block %.2f\n",
              static_cast<long>(n), ns_per([&] { gather_by_column(x, a.data(), y); }, d),
              ns_per([&] { gather_one_pass(x, a.data(), y); }, d),
              ns_per([&] { smc::gather_block(x.data(), n, n, 4, a.data(), n, y.data(), n); }, d));
}

void floor_and_sir(Eigen::Index n) {
  const double d = static_cast<double>(n);
  core::Rng source(1);
  core::LaneRng lanes(source);
  std::vector<float> normals(4 * static_cast<std::size_t>(n));
  std::vector<double> normals_double(4 * static_cast<std::size_t>(n));
  Eigen::VectorXd x = Eigen::VectorXd::Random(n) * 20.0, y(n);
  const double t_normals = ns_per([&] { lanes.fill_normal(normals.data(), normals.size()); }, d);
  const double t_normals_double =
      ns_per([&] { lanes.fill_normal(normals_double.data(), normals_double.size()); }, d);
  const double t_exp = ns_per([&] {
    const double* in = x.data();
    double* out = y.data();
    for (Eigen::Index i = 0; i < n; ++i) out[i] = core::vmath::exp(in[i]);
  }, d);
  std::printf("\nfloor, N = %ld: 4 normals %.2f ns (double precision: %.2f) + 1 exp %.2f ns = %.2f ns\n",
              static_cast<long>(n), t_normals, t_normals_double, t_exp, t_normals + t_exp);

  models::ConstantVelocityParams cv;
  cv.q = 0.25;
  const models::ConstantVelocity motion(cv);
  const models::RangeBearingObservation observation(models::RangeBearingParams{});
  const core::Gaussian prior(Eigen::Vector4d(120, 1, 60, 1.5),
                             Eigen::Matrix4d(Eigen::Vector4d(25, 1, 25, 1).asDiagonal()));
  smc::SirParams params;
  params.n_particles = static_cast<int>(n);
  smc::Sir<models::ConstantVelocity, models::RangeBearingObservation> sir(motion, observation, prior, params);
  Eigen::VectorXd z(2);
  z << 134.0, 0.46;
  smc::Sir<models::ConstantVelocity, models::RangeBearingObservation, smc::Bootstrap, float>
      sir_float(motion, observation, prior, params);
  const double t_step = ns_per([&] { sir.step(z); }, d, 51);
  const double t_float = ns_per([&] { sir_float.step(z); }, d, 51);
  for (const auto& [name, t] : {std::pair{"double", t_step}, std::pair{"float", t_float}}) {
    std::printf("SIR step, %s states (range-bearing, resampling every step): %.2f ns per particle "
                "= %.0f M particle-steps/s; floor / step = %.0f%%\n",
                name, t, 1e3 / t, 100.0 * (t_normals + t_exp) / t);
  }
}

}  // namespace

int main() {
  layout(100000);
  gather(100000);
  floor_and_sir(100000);
}

#include "vtrack/image/color_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#if defined(__AVX512BW__) && defined(__AVX512VBMI__)
#include <immintrin.h>
#endif

#include "vtrack/core/errors.hpp"

namespace vtrack::image {
namespace {

constexpr double kLog2Pi = 1.8378770664093453;  // log(2 pi)

bool is_empty(const Rect& r) { return r.width <= 0 || r.height <= 0; }
long long area(const Rect& r) {
  return is_empty(r) ? 0 : static_cast<long long>(r.width) * r.height;
}

Rect clip_to(const Rect& r, int cols, int rows) {
  const long long x0 = std::clamp<long long>(r.x, 0, cols);
  const long long y0 = std::clamp<long long>(r.y, 0, rows);
  const long long x1 = std::clamp<long long>(static_cast<long long>(r.x) + r.width, x0, cols);
  const long long y1 = std::clamp<long long>(static_cast<long long>(r.y) + r.height, y0, rows);
  return Rect{static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1 - x0),
              static_cast<int>(y1 - y0)};
}

// A box coordinate rounded to the pixel grid: floor(v + 0.5), with non-finite values and values
// beyond +-2^29 pinned so the int conversion and the difference of two such values are defined
// (such boxes are far outside any frame).
int round_px(double v) {
  constexpr double kLimit = 536870912.0;
  if (std::isnan(v)) return -static_cast<int>(kLimit);
  return static_cast<int>(std::clamp(std::floor(v + 0.5), -kLimit, kLimit));
}

// The incremental histograms (PixelCounts, PixelMoments) keep kCopies copies of their per-bin
// sums, pixel (x, y) in copy (x + y) mod kCopies, so a line's pixels go to the copies in turn
// whether it runs along a row or a column: neighbouring pixels, which often share a bin (uniform
// clothes, background), then update different copies, and their read-modify-writes do not wait
// on each other. Each copy is a sum over some of the box's pixels. Two copies (by the parity of
// x + y) -> four: update at N = 30 (benchmarks/cpp/color_micro.cpp) 50.1 -> 46.7 us kernel-
// weighted, 32.1 -> 29.0 us unweighted.
constexpr int kCopies = 4;

// Calls pixel(sum, x, y) for each pixel of `r` (clipped, inside the bin image's region), `sum`
// pointing at its bin's entry in its copy (of kCopies copies of m entries from `copies`), x, y its
// coordinates relative to the region's origin. Line by line along the rect's longer side: the
// strips between neighbouring boxes are mostly a few pixels wide and a box tall (at N = 30 on
// PETS09, 3100 of 4559 strip rows per frame were under 7 px), and a line has a set-up cost; as
// columns, update 75.9 -> 71.1 us (benchmarks/cpp/color_micro.cpp, kernel-weighted, N = 30).
template <class T, class Pixel>
void for_each_pixel(const HsvBinImage& bins, const Rect& r, T* copies, int m, Pixel pixel) {
  static_assert(kCopies == 4, "the walk below unrolls by kCopies");
  if (is_empty(r)) return;
  const int x0 = r.x - bins.roi().x, y0 = r.y - bins.roi().y;
  const std::uint16_t* first = bins.row_ptr(r.y) + x0;
  const std::ptrdiff_t stride = bins.roi().width;
  const bool by_rows = r.width >= r.height;
  const int lines = by_rows ? r.height : r.width, length = by_rows ? r.width : r.height;
  const std::ptrdiff_t line_step = by_rows ? stride : 1, step = by_rows ? 1 : stride;
  // The copies twice over: rotation + s lists copies s, s + 1, ... (mod kCopies).
  T* rotation[2 * kCopies];
  for (int k = 0; k < 2 * kCopies; ++k) {
    rotation[k] = copies + static_cast<std::ptrdiff_t>(k % kCopies) * m;
  }
  // Along a line one coordinate counts up from t0, across lines the other from f0.
  const auto walk = [&](int t0, int f0, auto xy) {
    for (int l = 0; l < lines; ++l) {
      const int f = f0 + l;
      const std::uint16_t* idx = first + l * line_step;
      T* const* copy = rotation + ((t0 + f) & (kCopies - 1));  // pixel i's is copy[i % kCopies]
      int i = 0;
      for (; i + 4 <= length; i += 4) {
        xy(copy[0] + idx[i * step], t0 + i, f);
        xy(copy[1] + idx[(i + 1) * step], t0 + i + 1, f);
        xy(copy[2] + idx[(i + 2) * step], t0 + i + 2, f);
        xy(copy[3] + idx[(i + 3) * step], t0 + i + 3, f);
      }
      for (int k = 0; i < length; ++i, ++k) xy(copy[k] + idx[i * step], t0 + i, f);
    }
  };
  if (by_rows) {
    walk(x0, y0, [&](T* sum, int x, int y) { pixel(sum, x, y); });
  } else {
    walk(y0, x0, [&](T* sum, int y, int x) { pixel(sum, x, y); });
  }
}

// counts[u] += 1 for each pixel of `r`, for whole boxes. Four partial histograms (`partial` holds
// 3 x bins of scratch) break the store-to-load dependency when neighbouring pixels share a bin
// (uniform clothes, background), the common case; the partial sums cost 4 x bins adds per box.
void count_rect(const HsvBinImage& bins, const Rect& r, std::int32_t* counts,
                std::int32_t* partial) {
  if (is_empty(r)) return;
  const int m = bins.bins();
  std::fill(partial, partial + 3 * m, 0);
  std::int32_t* p1 = partial;
  std::int32_t* p2 = partial + m;
  std::int32_t* p3 = partial + 2 * m;
  for (int row = r.y; row < r.y + r.height; ++row) {
    const std::uint16_t* idx = bins.row_ptr(row) + (r.x - bins.roi().x);
    int c = 0;
    for (; c + 4 <= r.width; c += 4) {
      ++counts[idx[c]];
      ++p1[idx[c + 1]];
      ++p2[idx[c + 2]];
      ++p3[idx[c + 3]];
    }
    for (; c < r.width; ++c) ++counts[idx[c]];
  }
  for (int u = 0; u < m; ++u) counts[u] += p1[u] + p2[u] + p3[u];
}

// Kernel-weighted histogram of the box (x, y, w, h) whose clipped pixel rect is `r`: hist[u] +=
// k(pixel) (file comment of the header). k = 1 - dx^2/a^2 - dy^2/a^2 splits into a row term and a
// column term: each row's weights are one vectorised pass, then scattered into four partial
// histograms (as count_rect). `scratch` holds 2 x width + 3 x bins doubles. Returns the total.
double add_kernel_rect(const HsvBinImage& bins, const Rect& r, double x, double y, double w,
                       double h, double* hist, std::vector<double>& scratch) {
  const double a2 = 0.25 * (w * w + h * h);
  if (is_empty(r) || !(a2 > 0)) return 0.0;
  const int m = bins.bins();
  const double cx = x + 0.5 * w, cy = y + 0.5 * h;
  scratch.assign(2 * static_cast<std::size_t>(r.width) + 3 * static_cast<std::size_t>(m), 0.0);
  double* column_term = scratch.data();
  double* k = column_term + r.width;
  double* p1 = k + r.width;
  double* p2 = p1 + m;
  double* p3 = p2 + m;
  for (int c = 0; c < r.width; ++c) {
    const double dx = r.x + c + 0.5 - cx;
    column_term[c] = dx * dx / a2;
  }
  double total = 0.0;
  for (int row = r.y; row < r.y + r.height; ++row) {
    const double dy = row + 0.5 - cy;
    const double row_term = 1.0 - dy * dy / a2;
    for (int c = 0; c < r.width; ++c) k[c] = std::max(0.0, row_term - column_term[c]);
    for (int c = 0; c < r.width; ++c) total += k[c];
    const std::uint16_t* idx = bins.row_ptr(row) + (r.x - bins.roi().x);
    int c = 0;
    for (; c + 4 <= r.width; c += 4) {
      hist[idx[c]] += k[c];
      p1[idx[c + 1]] += k[c + 1];
      p2[idx[c + 2]] += k[c + 2];
      p3[idx[c + 3]] += k[c + 3];
    }
    for (; c < r.width; ++c) hist[idx[c]] += k[c];
  }
  for (int u = 0; u < m; ++u) hist[u] += p1[u] + p2[u] + p3[u];
  return total;
}

// rho = sum_u sqrt(c_u / total) sqrt(q_u) (eq. 10) from unnormalised counts. Eight partial sums,
// so the compiler vectorises the square roots and the sum (8x faster than one running sum, with
// -fno-math-errno for this file: see CMakeLists.txt).
double rho_from_counts(const std::int32_t* counts, const float* sqrt_q, int m, long long total) {
  if (total <= 0) return 0.0;
  float acc[8] = {};
  int u = 0;
  for (; u + 8 <= m; u += 8) {
    for (int k = 0; k < 8; ++k) {
      acc[k] += std::sqrt(static_cast<float>(counts[u + k])) * sqrt_q[u + k];
    }
  }
  float s = 0.0f;
  for (; u < m; ++u) s += std::sqrt(static_cast<float>(counts[u])) * sqrt_q[u];
  for (const float a : acc) s += a;
  return std::min(1.0, static_cast<double>(s) / std::sqrt(static_cast<double>(total)));
}

double rho_from_weights(const double* hist, const float* sqrt_q, int m, double total) {
  if (!(total > 0)) return 0.0;
  double acc[4] = {};
  int u = 0;
  for (; u + 4 <= m; u += 4) {
    for (int k = 0; k < 4; ++k) {
      acc[k] += std::sqrt(hist[u + k]) * static_cast<double>(sqrt_q[u + k]);
    }
  }
  double s = acc[0] + acc[1] + acc[2] + acc[3];
  for (; u < m; ++u) s += std::sqrt(hist[u]) * static_cast<double>(sqrt_q[u]);
  return std::min(1.0, s / std::sqrt(total));
}

// The pieces of `a` outside `b` (at most 4 rectangles: full-width strips above and below `b`, then
// the parts left and right of `b` in the rows they share). Returns how many were written.
int difference(const Rect& a, const Rect& b, Rect* out) {
  const Rect i = intersect(a, b);
  if (is_empty(i)) {
    out[0] = a;
    return is_empty(a) ? 0 : 1;
  }
  int n = 0;
  const auto push = [&](int x, int y, int w, int h) {
    if (w > 0 && h > 0) out[n++] = Rect{x, y, w, h};
  };
  push(a.x, a.y, a.width, i.y - a.y);
  push(a.x, i.y + i.height, a.width, a.y + a.height - (i.y + i.height));
  push(a.x, i.y, i.x - a.x, i.height);
  push(i.x + i.width, i.y, a.x + a.width - (i.x + i.width), i.height);
  return n;
}

// Interleaves the low 16 bits of x and y (Z-order), so nearby corners get nearby codes.
std::uint32_t morton(std::uint32_t x, std::uint32_t y) {
  const auto spread = [](std::uint32_t v) {
    v &= 0xFFFF;
    v = (v | (v << 8)) & 0x00FF00FF;
    v = (v | (v << 4)) & 0x0F0F0F0F;
    v = (v | (v << 2)) & 0x33333333;
    v = (v | (v << 1)) & 0x55555555;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}

bool same_bins(const ColorHistogramParams& a, const ColorHistogramParams& b) {
  return a.bins_h == b.bins_h && a.bins_s == b.bins_s && a.bins_v == b.bins_v;
}

// The clipped pixel rects of n boxes, each checked to lie inside the bin image's region.
std::vector<Rect> clipped_rects(const HsvBinImage& bins, const double* boxes, std::size_t n,
                                std::size_t stride) {
  std::vector<Rect> rects(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* b = boxes + i * stride;
    rects[i] = bins.clip_inside(pixel_rect(b[0], b[1], b[2], b[3]));
  }
  return rects;
}

void coefficients_direct(const HsvBinImage& bins, const double* boxes, std::size_t stride,
                         const std::vector<Rect>& rects, bool kernel, const float* sqrt_q,
                         double* rho) {
  const int m = bins.bins();
  if (kernel) {
    std::vector<double> hist(static_cast<std::size_t>(m)), scratch;
    for (std::size_t i = 0; i < rects.size(); ++i) {
      const double* b = boxes + i * stride;
      std::fill(hist.begin(), hist.end(), 0.0);
      const double total =
          add_kernel_rect(bins, rects[i], b[0], b[1], b[2], b[3], hist.data(), scratch);
      rho[i] = rho_from_weights(hist.data(), sqrt_q, m, total);
    }
    return;
  }
  std::vector<std::int32_t> counts(static_cast<std::size_t>(4 * m));
  for (std::size_t i = 0; i < rects.size(); ++i) {
    std::fill(counts.begin(), counts.begin() + m, 0);
    count_rect(bins, rects[i], counts.data(), counts.data() + m);
    rho[i] = rho_from_counts(counts.data(), sqrt_q, m, area(rects[i]));
  }
}

// Unweighted histograms for the incremental method: per-bin pixel counts.
class PixelCounts {
 public:
  PixelCounts(int m, const float*) : m_(m), counts_(static_cast<std::size_t>((kCopies + 1) * m)) {}
  void count(const HsvBinImage& bins, const Rect& r) {
    std::fill(counts_.begin(), counts_.end(), 0);
    add<1>(bins, r);
  }
  template <int Sign>
  void add(const HsvBinImage& bins, const Rect& r) {
    for_each_pixel(bins, r, counts_.data(), m_, [](std::int32_t* n, int, int) { *n += Sign; });
  }
  double rho(const HsvBinImage&, const Rect& r, const double*, const float* sqrt_q) {
    std::int32_t* total = counts_.data() + kCopies * m_;
    for (int u = 0; u < m_; ++u) {
      total[u] = (counts_[u] + counts_[m_ + u]) + (counts_[2 * m_ + u] + counts_[3 * m_ + u]);
    }
    return rho_from_counts(total, sqrt_q, m_, area(r));
  }

 private:
  int m_;
  std::vector<std::int32_t> counts_;  // kCopies copies of the m counts, then their sum (rho())
};

// Kernel-weighted histograms for the incremental method. The Epanechnikov weight of a pixel,
// k = 1 - (dx^2 + dy^2) / a^2, is a polynomial in its coordinates, so a bin's total weight
//   hist[u] = sum_{pixels in u} k = n_u - (S_u - 2 ex X_u - 2 ey Y_u + (ex^2 + ey^2) n_u) / a^2
// follows from four per-bin moments of its pixels' coordinates (x, y) relative to the region's
// origin -- the count n_u, X_u = sum x, Y_u = sum y, S_u = sum (x^2 + y^2) -- and the box's
// centre (ex, ey) in those coordinates (dx = x - ex, dy = y - ey, pixel centres at +0.5). The
// moments do not depend on the box's centre or size, so they are updated by the pixels that
// change between neighbouring boxes, as counts are. They are integers held in doubles: exact,
// whatever order pixels are added and removed in, while below 2^53 (any region up to 8192 x 8192
// pixels). No pixel weight is negative (every pixel centre of a box lies inside the continuous
// box, so r <= a), which is why the per-pixel max(0, k) of add_kernel_rect is not needed here: a
// bin is clamped at 0 only against rounding, and the total weight has a closed form over the
// box's rows and columns. Only the template's non-empty bins enter rho (eq. 10), so only they are
// evaluated. A bin's four moments are one 32-byte vector, so a pixel costs one vector
// read-modify-write (GCC/Clang vector extensions; AVX2 with -march=native), into one of kCopies
// copies (for_each_pixel; one copy: 244 us per update at N = 30, benchmarks/cpp/color_micro.cpp;
// two: 178; four, then row by row: no better than two).
class PixelMoments {
 public:
  PixelMoments(int m, const float* sqrt_q)
      : m_(m), moments_(static_cast<std::size_t>(kCopies * m)) {
    std::vector<double> q;
    for (int u = 0; u < m; ++u) {
      if (sqrt_q[u] > 0.0f) {
        support_.push_back(u);
        q.push_back(sqrt_q[u]);
      }
    }
    // Padded to whole groups of 4 with bin 0 at sqrt_q 0, which adds exactly 0 to rho.
    while (support_.size() % 4 != 0) {
      support_.push_back(0);
      q.push_back(0.0);
    }
    for (std::size_t j = 0; j < q.size(); j += 4) {
      sqrt_q_.push_back(Moments{q[j], q[j + 1], q[j + 2], q[j + 3]});
    }
  }
  void count(const HsvBinImage& bins, const Rect& r) {
    std::fill(moments_.begin(), moments_.end(), Moments{0.0, 0.0, 0.0, 0.0});
    add<1>(bins, r);
  }
  template <int Sign>
  void add(const HsvBinImage& bins, const Rect& r) {
    for_each_pixel(bins, r, moments_.data(), m_, [](Moments* sum, int x, int y) {
      const double dx = x, dy = y;
      *sum += Moments{1.0, dx, dy, dx * dx + dy * dy} * Sign;
    });
  }
  // rho of the box b = (x, y, w, h), whose clipped pixel rect is r (eq. 10).
  double rho(const HsvBinImage& bins, const Rect& r, const double* b, const float*) const {
    const double a2 = 0.25 * (b[2] * b[2] + b[3] * b[3]);
    const double ex = b[0] + 0.5 * b[2] - 0.5 - bins.roi().x;
    const double ey = b[1] + 0.5 * b[3] - 0.5 - bins.roi().y;
    if (is_empty(r) || !(a2 > 0) || !std::isfinite(a2 + ex + ey)) return 0.0;
    // sum over the rect's pixels of dx^2 + dy^2, from the rows' and columns' sums.
    const double w = r.width, h = r.height;
    const auto squares = [](double e, double n) {  // sum_{j < n} (e + j)^2
      return n * e * e + e * n * (n - 1) + (n - 1) * n * (2 * n - 1) / 6;
    };
    const double spread = h * squares(r.x - bins.roi().x - ex, w) +
                          w * squares(r.y - bins.roi().y - ey, h);
    const double total = w * h - spread / a2;
    if (!(total > 0.0)) return 0.0;
    const Moments coef = {1.0 - (ex * ex + ey * ey) / a2, 2.0 * ex / a2, 2.0 * ey / a2, -1.0 / a2};
    // Four bins at a time: their weights, each (t0 + t1) + (t2 + t3) of t = coef * moments, in
    // one vector, then four square roots and four products in vector operations (a scalar loop
    // over the bins spent ~10 % of an update on the square roots and the sum's dependency chain).
    typedef long long Pick __attribute__((vector_size(32)));
    static_assert(kCopies == 4, "rho sums four copies");
    const Moments *c0 = moments_.data(), *c1 = c0 + m_, *c2 = c1 + m_, *c3 = c2 + m_;
    Moments acc = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t j = 0; j < support_.size(); j += 4) {
      Moments t[4];
      for (int k = 0; k < 4; ++k) {
        const auto u = static_cast<std::size_t>(support_[j + k]);
        t[k] = coef * ((c0[u] + c1[u]) + (c2[u] + c3[u]));
      }
      const Moments t01 = __builtin_shuffle(t[0], t[1], Pick{0, 4, 2, 6}) +
                          __builtin_shuffle(t[0], t[1], Pick{1, 5, 3, 7});
      const Moments t23 = __builtin_shuffle(t[2], t[3], Pick{0, 4, 2, 6}) +
                          __builtin_shuffle(t[2], t[3], Pick{1, 5, 3, 7});
      Moments weight = __builtin_shuffle(t01, t23, Pick{0, 1, 4, 5}) +
                       __builtin_shuffle(t01, t23, Pick{2, 3, 6, 7});
      weight = weight > 0.0 ? weight : 0.0;  // clamped against rounding
      Moments root;
      for (int k = 0; k < 4; ++k) root[k] = std::sqrt(weight[k]);
      acc += root * sqrt_q_[j / 4];
    }
    const double s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    return std::min(1.0, s / std::sqrt(total));
  }

 private:
  // n, X, Y, S of one bin.
  typedef double Moments __attribute__((vector_size(32)));

  int m_;
  std::vector<Moments> moments_;  // kCopies copies of the m bins' moments
  std::vector<int> support_;      // the template's non-empty bins, padded (constructor)
  std::vector<Moments> sqrt_q_;   // their sqrt(q), four per vector
};

// Pixels counted to go from the histogram of `from` to that of `to`: the symmetric difference,
// or `to` afresh when that is smaller.
long long update_cost(const Rect& from, const Rect& to) {
  if (is_empty(from)) return area(to);
  return std::min(area(to), area(from) + area(to) - 2 * area(intersect(from, to)));
}

// The order in which the incremental method counts the non-empty rects: a greedy chain, each next
// rect the one that costs least (update_cost) from the last among the not yet counted within the
// kWindow positions of Morton order (of the corners) from the first not yet counted; the first
// the smallest there. Morton order alone jumps between quadrants of the cloud, where a box is
// counted afresh: on PETS09 (benchmarks/cpp/color_micro.cpp, the colour PF's clouds) the chain
// counts 24 % fewer pixels per frame at N = 30 (38.7k against 50.9k) and 35 % fewer at N = 210
// (170k against 262k). The order changes no result (counts and moments are exact, whatever the
// order), only the time.
//
// The window's costs are one branch-free loop over the rects' corners in Morton order (int32
// arrays, which the compiler vectorises) reduced to the least key cost * kWindow + offset, so
// ties go to the first in Morton order; counted rects key INT32_MAX. Scalar costs, and a list
// erased from as rects were counted, took a third of the unweighted coefficients at N = 210.
std::vector<std::uint32_t> counting_order(const HsvBinImage& bins, const std::vector<Rect>& rects) {
  constexpr int kWindow = 64;
  // Keys stay below 2^31 with costs capped at 2^24 pixels (any frame up to 4096 x 4096; a cap
  // would change only the order).
  constexpr std::int32_t kMaxCost = 1 << 24, kCounted = INT32_MAX;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> morton_order;
  for (std::size_t i = 0; i < rects.size(); ++i) {
    if (is_empty(rects[i])) continue;
    morton_order.emplace_back(morton(static_cast<std::uint32_t>(rects[i].x - bins.roi().x),
                                     static_cast<std::uint32_t>(rects[i].y - bins.roi().y)),
                              static_cast<std::uint32_t>(i));
  }
  std::sort(morton_order.begin(), morton_order.end());
  const std::size_t n = morton_order.size();
  // Corners relative to the region, in Morton order, and kWindow entries past the end that key
  // kCounted (so that a window never needs a bounds check).
  std::vector<std::int32_t> x0(n + kWindow), y0(n + kWindow), x1(n + kWindow), y1(n + kWindow),
      counted(n + kWindow, kCounted);
  for (std::size_t k = 0; k < n; ++k) {
    const Rect& r = rects[morton_order[k].second];
    x0[k] = r.x - bins.roi().x, y0[k] = r.y - bins.roi().y;
    x1[k] = x0[k] + r.width, y1[k] = y0[k] + r.height;
    counted[k] = 0;
  }
  std::vector<std::uint32_t> order;
  order.reserve(n);
  std::int32_t px0 = 0, py0 = 0, px1 = 0, py1 = 0;  // the last rect counted (none: empty)
  std::size_t first = 0;  // the first not yet counted in Morton order
  for (std::size_t picked = 0; picked < n; ++picked) {
    const std::int32_t prev_area = (px1 - px0) * (py1 - py0);
    std::int32_t best = kCounted;
    for (int k = 0; k < kWindow; ++k) {
      const std::size_t j = first + static_cast<std::size_t>(k);
      const std::int32_t area = (x1[j] - x0[j]) * (y1[j] - y0[j]);
      const std::int32_t iw = std::max(0, std::min(x1[j], px1) - std::max(x0[j], px0));
      const std::int32_t ih = std::max(0, std::min(y1[j], py1) - std::max(y0[j], py0));
      const std::int32_t cost = std::min({area, prev_area + area - 2 * iw * ih, kMaxCost});
      best = std::min(best, std::max(cost * kWindow + k, counted[j]));
    }
    const std::size_t j = first + static_cast<std::size_t>(best % kWindow);
    order.push_back(morton_order[j].second);
    counted[j] = kCounted;
    px0 = x0[j], py0 = y0[j], px1 = x1[j], py1 = y1[j];
    while (first < n && counted[first] != 0) ++first;
  }
  return order;
}

// Each box's histogram from the previous box's in counting_order: remove the pixels of
// prev \ box, add those of box \ prev, or count afresh when that is cheaper. `Histogram` is
// PixelCounts or PixelMoments.
template <class Histogram>
void coefficients_incremental(const HsvBinImage& bins, const double* boxes, std::size_t stride,
                              const std::vector<Rect>& rects, const float* sqrt_q, double* rho) {
  for (std::size_t i = 0; i < rects.size(); ++i) rho[i] = 0.0;  // empty rects stay 0
  Histogram hist(bins.bins(), sqrt_q);
  Rect prev{};
  Rect pieces[4];
  for (const std::uint32_t i : counting_order(bins, rects)) {
    const Rect& r = rects[i];
    if (is_empty(prev) || update_cost(prev, r) >= area(r)) {
      hist.count(bins, r);
    } else {
      const int gone = difference(prev, r, pieces);
      for (int k = 0; k < gone; ++k) hist.template add<-1>(bins, pieces[k]);
      const int added = difference(r, prev, pieces);
      for (int k = 0; k < added; ++k) hist.template add<1>(bins, pieces[k]);
    }
    prev = r;
    rho[i] = hist.rho(bins, r, boxes + i * stride, sqrt_q);
  }
}

// OpenCV's 8-bit BGR -> HSV_FULL (imgproc's RGB2HSV_b with hrange 256), integer for integer: the
// reciprocal tables sdiv[v] = round(255 * 2^12 / v) and hdiv[d] = round(256 * 2^12 / (6 d)), then
//   S = (diff * sdiv[V] + 2^11) >> 12,  H = (h' * hdiv[diff] + 2^11) >> 12 (+ 256 if < 0),
// with h' = G - B if V = R, else B - R + 2 diff if V = G, else R - G + 4 diff. Bit-exact with
// cv::cvtColor(COLOR_BGR2HSV_FULL) for all 2^24 colors (tested); done here, fused with the
// binning, because cvtColor on a narrow region of a frame (a person is 20-60 px wide) pays its
// per-row set-up on every row and spreads large regions over OpenCV's threads. A channel value c
// with n bins falls in bin floor(c * n / 256), i.e. (c * n) >> 8 (arithmetic, not three table
// lookups: branch-free).
#if defined(__AVX512BW__) && defined(__AVX512VBMI__)
// 16 pixels per vector of 32-bit lanes. The tables' entries are computed in the lanes rather than
// looked up (AVX-512 has no cheap 256-entry lookup: gathers are slow on AMD, a permutation tree
// costs 7 instructions): sdiv[v] is 1044480 / v rounded to nearest-even, and the single-precision
// quotient, correctly rounded, never falls on the other side of a half-integer (the true quotient
// is a multiple of 1 / v, so it lies 1 / (2 v) or more from one unless it is one, exactly
// representable, while the float's error is under 2^-24 1044480 / v = 0.06 / v); the same holds
// for hdiv's 1048576 / (6 d) (>= 1 / (12 d) away, error under 0.011 / d). v = 0 or d = 0 give an
// infinite quotient, whose conversion is INT_MIN, but it is then multiplied by diff = 0 or h' = 0.
// On a hot frame (benchmarks/cpp/color_micro.cpp, rows of ~100 px) 0.35 ns per pixel, against 1.27
// for the scalar loop below as GCC vectorises it (benchmarks/follow.py: the whole update).
class RowQuantiser {
 public:
  explicit RowQuantiser(const ColorHistogramParams& p)
      : bins_h_(p.bins_h), bins_s_(p.bins_s), bins_v_(p.bins_v), h_stride_(p.bins_s * p.bins_v) {
    // Byte 4k of channel c's index picks byte 3k + c (pixel k's B, G or R) of 16 packed pixels.
    alignas(64) unsigned char index[3][64];
    for (int c = 0; c < 3; ++c) {
      for (int i = 0; i < 64; ++i) index[c][i] = static_cast<unsigned char>(3 * (i / 4) + c);
    }
    for (int c = 0; c < 3; ++c) channel_[c] = _mm512_load_si512(index[c]);
  }

  void operator()(const unsigned char* bgr, int n, std::uint16_t* out) const {
    int c = 0;
    for (; c + 16 <= n; c += 16) {
      const Lanes u = bins(load48(bgr + 3 * c), channel_);
      const auto u16 = __builtin_convertvector(u, std::int16_t __attribute__((vector_size(32))));
      std::memcpy(out + c, &u16, sizeof(u16));
    }
    if (c == n) return;
    // The last 1-15 pixels. A masked load still fetches every cache line of its 64 bytes, and the
    // line after the row is not in cache (nor prefetched): it cost a DRAM wait per row. So the
    // load is of the 64 bytes ending with the row's last byte when the row has that many, the
    // channels' byte indices shifted to match; a masked store writes only the pixels' bins. (The
    // same for the 16-pixel loads: 48 bytes exactly.)
    const int rest = n - c;
    Lanes u;
    if (3 * n >= 64) {
      const __m512i shift = _mm512_set1_epi8(static_cast<char>(64 - 3 * rest));
      const __m512i channel[3] = {_mm512_add_epi8(channel_[0], shift),
                                  _mm512_add_epi8(channel_[1], shift),
                                  _mm512_add_epi8(channel_[2], shift)};
      u = bins(_mm512_loadu_si512(bgr + 3 * n - 64), channel);
    } else {
      u = bins(_mm512_maskz_loadu_epi8((1ULL << (3 * rest)) - 1, bgr + 3 * c), channel_);
    }
    _mm512_mask_cvtepi32_storeu_epi16(out + c, static_cast<__mmask16>((1u << rest) - 1),
                                      reinterpret_cast<__m512i>(u));
  }

 private:
  // GCC vector extensions for the arithmetic (plain operators; GCC 12's AVX-512 intrinsics for it
  // raise false -Wmaybe-uninitialized warnings), intrinsics for the rest.
  typedef std::int32_t Lanes __attribute__((vector_size(64)));
  typedef float FloatLanes __attribute__((vector_size(64)));

  // The 48 bytes at p in the low bytes of a vector (the rest undefined, never picked).
  static __m512i load48(const unsigned char* p) {
    const __m256i low = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
    const __m128i high = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 32));
    return _mm512_inserti32x4(_mm512_castsi256_si512(low), high, 2);
  }

  // Round to nearest-even (maskz: the plain intrinsic trips the same GCC 12 warning).
  static Lanes round(FloatLanes x) {
    return reinterpret_cast<Lanes>(_mm512_maskz_cvt_roundps_epi32(
        0xFFFF, reinterpret_cast<__m512>(x), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  }

  // Bin indices of 16 pixels packed in `px` (B, G, R each), whose bytes `index` picks (channel_
  // for the low 48 bytes).
  Lanes bins(__m512i px, const __m512i* index) const {
    constexpr __mmask64 kLow = 0x1111111111111111ULL;  // the low byte of each 32-bit lane
    const auto channel = [&](int c) {
      return reinterpret_cast<Lanes>(_mm512_maskz_permutexvar_epi8(kLow, index[c], px));
    };
    const Lanes b = channel(0), g = channel(1), r = channel(2);
    const auto max = [](Lanes x, Lanes y) { return x > y ? x : y; };
    const auto min = [](Lanes x, Lanes y) { return x < y ? x : y; };
    const Lanes v = max(max(b, g), r);
    const Lanes diff = v - min(min(b, g), r);
    const Lanes sdiv = round(float{255 << 12} / __builtin_convertvector(v, FloatLanes));
    const Lanes hdiv = round(float{256 << 12} / (6.0f * __builtin_convertvector(diff, FloatLanes)));
    const Lanes s = (diff * sdiv + (1 << 11)) >> 12;
    const Lanes hue = v == r ? g - b : (v == g ? b - r + 2 * diff : r - g + 4 * diff);
    // H in [-256, 255] before the wrap; & 255 adds 256 to the negative ones.
    const Lanes h = ((hue * hdiv + (1 << 11)) >> 12) & 255;
    return ((h * bins_h_) >> 8) * h_stride_ + ((s * bins_s_) >> 8) * bins_v_ + ((v * bins_v_) >> 8);
  }

  __m512i channel_[3];
  int bins_h_, bins_s_, bins_v_, h_stride_;
};
#else
struct HsvTables {
  int sdiv[256];
  int hdiv[256];
};

const HsvTables& hsv_tables() {
  static const HsvTables tables = [] {
    HsvTables t{};
    for (int i = 1; i < 256; ++i) {
      t.sdiv[i] = static_cast<int>(std::lrint((255 << 12) / (1.0 * i)));
      t.hdiv[i] = static_cast<int>(std::lrint((256 << 12) / (6.0 * i)));
    }
    return t;
  }();
  return tables;
}

// One pixel at a time (GCC vectorises the loop).
class RowQuantiser {
 public:
  explicit RowQuantiser(const ColorHistogramParams& p) : p_(p), t_(hsv_tables()) {}

  void operator()(const unsigned char* __restrict bgr, int n, std::uint16_t* __restrict out) const {
    const int bh = p_.bins_h, bs = p_.bins_s, bv = p_.bins_v, h_stride = bs * bv;
    for (int c = 0; c < n; ++c) {
      const int b = bgr[3 * c], g = bgr[3 * c + 1], r = bgr[3 * c + 2];
      const int v = std::max(std::max(b, g), r);
      const int diff = v - std::min(std::min(b, g), r);
      const int s = (diff * t_.sdiv[v] + (1 << 11)) >> 12;
      const int hue = v == r ? g - b : (v == g ? b - r + 2 * diff : r - g + 4 * diff);
      int h = (hue * t_.hdiv[diff] + (1 << 11)) >> 12;
      h += h < 0 ? 256 : 0;
      out[c] = static_cast<std::uint16_t>(((h * bh) >> 8) * h_stride + ((s * bs) >> 8) * bv +
                                          ((v * bv) >> 8));
    }
  }

 private:
  ColorHistogramParams p_;
  const HsvTables& t_;
};
#endif

}  // namespace

const core::ParameterTable<ColorHistogramParams>& ColorHistogramParams::table() {
  using P = ColorHistogramParams;
  static const auto t = core::ParameterTable<P>()
                            .add("bins_h", &P::bins_h)
                            .add("bins_s", &P::bins_s)
                            .add("bins_v", &P::bins_v)
                            .add("kernel", &P::kernel);
  return t;
}

void validate(const ColorHistogramParams& p) {
  require(p.bins_h >= 1 && p.bins_h <= 256, "bins_h", p.bins_h, "in [1, 256]");
  require(p.bins_s >= 1 && p.bins_s <= 256, "bins_s", p.bins_s, "in [1, 256]");
  require(p.bins_v >= 1 && p.bins_v <= 256, "bins_v", p.bins_v, "in [1, 256]");
  // Bin indices are 16-bit.
  require(bin_count(p) <= 65536, "bins_h * bins_s * bins_v", bin_count(p), "at most 65536");
}

Rect pixel_rect(double x, double y, double w, double h) {
  const int x0 = round_px(x), y0 = round_px(y);
  const int x1 = round_px(x + w), y1 = round_px(y + h);
  return Rect{x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

Rect boxes_roi(const double* boxes, std::size_t n, std::size_t stride, int cols, int rows) {
  int x0 = cols, y0 = rows, x1 = 0, y1 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double* b = boxes + i * stride;
    const Rect r = clip_to(pixel_rect(b[0], b[1], b[2], b[3]), cols, rows);
    if (is_empty(r)) continue;
    x0 = std::min(x0, r.x);
    y0 = std::min(y0, r.y);
    x1 = std::max(x1, r.x + r.width);
    y1 = std::max(y1, r.y + r.height);
  }
  if (x1 <= x0 || y1 <= y0) return Rect{};
  return Rect{x0, y0, x1 - x0, y1 - y0};
}

HsvBinImage::HsvBinImage(const ColorHistogramParams& params) : params_(params) {
  validate(params_);
}

void HsvBinImage::assign(const cv::Mat& bgr, const Rect& roi) {
  if (bgr.empty()) throw InvalidArgument("frame is empty");
  if (bgr.type() != CV_8UC3) {
    throw InvalidArgument("frame must be 8-bit with 3 channels (BGR), got depth " +
                          std::to_string(bgr.depth()) + " with " + std::to_string(bgr.channels()) +
                          " channels");
  }
  frame_rows_ = bgr.rows;
  frame_cols_ = bgr.cols;
  roi_ = clip_to(roi, bgr.cols, bgr.rows);
  if (is_empty(roi_)) {
    roi_ = Rect{};
    return;
  }
  buffer_.resize(static_cast<std::size_t>(roi_.width) * roi_.height);
  // Each row of the region starts a new stretch of the frame (a stride apart, a new page every
  // row or two), which the hardware prefetcher does not anticipate; a frame that is not in cache
  // (a tracker fed frames decoded earlier) then stalls on every row's first lines. Asking for the
  // row kPrefetchRows ahead hides that wait (benchmarks/cpp/color_micro.cpp).
  constexpr int kPrefetchRows = 4;
  const std::size_t row_bytes = 3 * static_cast<std::size_t>(roi_.width);
  const RowQuantiser quantise_row(params_);
  for (int row = 0; row < roi_.height; ++row) {
    if (row + kPrefetchRows < roi_.height) {
      // Every cache line the row's bytes touch, from the one holding its first byte (64-byte
      // steps from the first byte itself miss the last line when the row starts mid-line).
      const auto ahead = reinterpret_cast<std::uintptr_t>(
          bgr.ptr<unsigned char>(roi_.y + row + kPrefetchRows) + 3 * roi_.x);
      for (std::uintptr_t a = ahead & ~std::uintptr_t{63}; a < ahead + row_bytes; a += 64) {
        __builtin_prefetch(reinterpret_cast<const void*>(a), 0, 3);
      }
    }
    quantise_row(bgr.ptr<unsigned char>(roi_.y + row) + 3 * roi_.x, roi_.width,
                 buffer_.data() + static_cast<std::size_t>(row) * roi_.width);
  }
}

Rect HsvBinImage::clip_inside(const Rect& rect) const {
  const Rect r = clip_to(rect, frame_cols_, frame_rows_);
  if (is_empty(r)) return Rect{r.x, r.y, 0, 0};
  if (r.x < roi_.x || r.y < roi_.y || r.x + r.width > roi_.x + roi_.width ||
      r.y + r.height > roi_.y + roi_.height) {
    const auto span = [](int a, int b) {
      return "[" + std::to_string(a) + ", " + std::to_string(b) + ")";
    };
    throw InvalidArgument("box pixels " + span(r.x, r.x + r.width) + " x " +
                          span(r.y, r.y + r.height) + " lie outside the quantised region " +
                          span(roi_.x, roi_.x + roi_.width) + " x " +
                          span(roi_.y, roi_.y + roi_.height));
  }
  return r;
}

double box_histogram(const HsvBinImage& bins, double x, double y, double w, double h, bool kernel,
                     double* hist) {
  const int m = bins.bins();
  std::fill(hist, hist + m, 0.0);
  const Rect r = bins.clip_inside(pixel_rect(x, y, w, h));
  if (kernel) {
    std::vector<double> scratch;
    return add_kernel_rect(bins, r, x, y, w, h, hist, scratch);
  }
  std::vector<std::int32_t> counts(static_cast<std::size_t>(4 * m), 0);
  count_rect(bins, r, counts.data(), counts.data() + m);
  std::copy(counts.begin(), counts.begin() + m, hist);
  return static_cast<double>(area(r));
}

double bhattacharyya_coefficient(const double* p, const double* q, std::size_t m) {
  double sp = 0.0, sq = 0.0, s = 0.0;
  for (std::size_t u = 0; u < m; ++u) {
    if (!(p[u] >= 0.0)) require(false, "p", p[u], "non-negative (every bin)");
    if (!(q[u] >= 0.0)) require(false, "q", q[u], "non-negative (every bin)");
    sp += p[u];
    sq += q[u];
    s += std::sqrt(p[u] * q[u]);
  }
  require(sp > 0.0 && std::isfinite(sp), "sum of p", sp, "positive and finite");
  require(sq > 0.0 && std::isfinite(sq), "sum of q", sq, "positive and finite");
  return std::min(1.0, s / std::sqrt(sp * sq));
}

double bhattacharyya_distance(double rho) { return std::sqrt(std::max(0.0, 1.0 - rho)); }

double color_log_likelihood(double rho, double sigma) {
  require(sigma > 0.0 && std::isfinite(sigma), "sigma", sigma, "positive and finite");
  return -0.5 * kLog2Pi - std::log(sigma) - (1.0 - rho) / (2.0 * sigma * sigma);
}

void color_log_likelihood(const double* rho, std::size_t n, double sigma, double* out) {
  require(sigma > 0.0 && std::isfinite(sigma), "sigma", sigma, "positive and finite");
  const double offset = -0.5 * kLog2Pi - std::log(sigma);
  const double scale = 1.0 / (2.0 * sigma * sigma);
  for (std::size_t i = 0; i < n; ++i) out[i] = offset - (1.0 - rho[i]) * scale;
}

ColorModel::ColorModel(const ColorHistogramParams& params, const std::vector<double>& hist)
    : params_(params) {
  validate(params_);
  const auto m = static_cast<std::size_t>(bin_count(params_));
  if (hist.size() != m) {
    throw InvalidArgument("template histogram must have " + std::to_string(m) + " bins, got " +
                          std::to_string(hist.size()));
  }
  double total = 0.0;
  for (double v : hist) {
    require(v >= 0.0 && std::isfinite(v), "template histogram bin", v, "non-negative and finite");
    total += v;
  }
  require(total > 0.0, "template histogram sum", total, "positive (the box has no pixel)");
  q_.resize(m);
  sqrt_q_.resize(m);
  for (std::size_t u = 0; u < m; ++u) {
    q_[u] = hist[u] / total;
    sqrt_q_[u] = static_cast<float>(std::sqrt(q_[u]));
  }
}

ColorModel ColorModel::from_box(const cv::Mat& bgr, double x, double y, double w, double h,
                                  const ColorHistogramParams& params) {
  HsvBinImage bins(params);
  bins.assign(bgr, pixel_rect(x, y, w, h));
  std::vector<double> hist(static_cast<std::size_t>(bins.bins()));
  if (!(box_histogram(bins, x, y, w, h, params.kernel, hist.data()) > 0.0)) {
    throw InvalidArgument("box (" + value_text(x) + ", " + value_text(y) + ", " + value_text(w) +
                          ", " + value_text(h) + ") has no pixel inside the " +
                          std::to_string(bgr.cols) + " x " + std::to_string(bgr.rows) + " frame");
  }
  return ColorModel(params, hist);
}

}  // namespace vtrack::image

namespace vtrack::image {

void ColorModel::coefficients(const HsvBinImage& bins, const double* boxes, std::size_t n,
                               std::size_t stride, double* rho, HistogramMethod method) const {
  if (!same_bins(bins.params(), params_)) {
    throw InvalidArgument("the bin image has " + std::to_string(bins.params().bins_h) + " x " +
                          std::to_string(bins.params().bins_s) + " x " +
                          std::to_string(bins.params().bins_v) + " bins, the model " +
                          std::to_string(params_.bins_h) + " x " + std::to_string(params_.bins_s) +
                          " x " + std::to_string(params_.bins_v));
  }
  if (n == 0) return;
  require(stride >= 4, "stride", static_cast<double>(stride), "at least 4 (x, y, w, h)");
  const std::vector<Rect> rects = clipped_rects(bins, boxes, n, stride);
  // automatic: incremental (it was faster than direct counting for every box size, particle
  // count and spread measured in benchmarks/color_histogram.py, weighted or not).
  if (method == HistogramMethod::direct) {
    coefficients_direct(bins, boxes, stride, rects, params_.kernel, sqrt_q_.data(), rho);
  } else if (params_.kernel) {
    coefficients_incremental<PixelMoments>(bins, boxes, stride, rects, sqrt_q_.data(), rho);
  } else {
    coefficients_incremental<PixelCounts>(bins, boxes, stride, rects, sqrt_q_.data(), rho);
  }
}

void ColorModel::coefficients(const cv::Mat& bgr, const double* boxes, std::size_t n,
                               std::size_t stride, double* rho, HsvBinImage& workspace,
                               HistogramMethod method) const {
  if (!same_bins(workspace.params(), params_)) workspace = HsvBinImage(params_);
  require(stride >= 4, "stride", static_cast<double>(stride), "at least 4 (x, y, w, h)");
  if (bgr.empty()) throw InvalidArgument("frame is empty");
  workspace.assign(bgr, boxes_roi(boxes, n, stride, bgr.cols, bgr.rows));
  coefficients(workspace, boxes, n, stride, rho, method);
}

}  // namespace vtrack::image

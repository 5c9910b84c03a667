#pragma once
// Gathering particles by ancestor index after resampling: dst(j, c) = src(ancestors[j], c) for
// column-major arrays, one particle per row.
//
// Resampling's gather is one of the largest stages of a SIR step (a load and a store per
// component and particle). Two things make it cheaper:
//  - one pass over the ancestors copies every column, so each index is read once per particle
//    rather than once per component;
//  - with AVX-512, ancestors that lie within one small window (as systematic, stratified and
//    residual resampling produce: sorted, about one copy each, so 16 consecutive ancestors
//    span ~16 particles) are gathered by a two-register permutation: two vector loads of the
//    window and one permute per component and 16 floats (8 doubles), instead of 16 scalar loads
//    and stores. Ancestors outside such a window take the scalar path.
// 4 float columns at N = 1e5 (benchmarks/cpp/smc_micro.cpp): column by column 1.05 ns per
// particle, one pass 0.90, with the permutation 0.49.
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace vtrack::smc {

namespace gather_detail {

template <int Cols, typename T>
void scalar_rows(const T* const* from, T* const* to, const std::int64_t* ancestors,
                 Eigen::Index begin, Eigen::Index end) {
  for (Eigen::Index j = begin; j < end; ++j) {
    const std::int64_t k = ancestors[j];
    for (int c = 0; c < Cols; ++c) to[c][j] = from[c][k];
  }
}

#if defined(__AVX512F__)
// Rows [j, j + kLanes) by permutation when every ancestor lies in [base, base + 2 kLanes) and
// that window lies inside the source (src_rows rows); false (nothing written) otherwise.
template <int Cols, typename T>
bool permuted_rows(const T* const* from, T* const* to, const std::int64_t* ancestors,
                   Eigen::Index j, Eigen::Index src_rows) {
  const std::int64_t base = ancestors[j];
  const __m512i vbase = _mm512_set1_epi64(base);
  const __m512i window = _mm512_set1_epi64(2 * (64 / static_cast<int>(sizeof(T))));
  if (base + 2 * (64 / static_cast<std::int64_t>(sizeof(T))) > src_rows) return false;
  if constexpr (sizeof(T) == 4) {
    const __m512i lo = _mm512_sub_epi64(_mm512_loadu_si512(ancestors + j), vbase);
    const __m512i hi = _mm512_sub_epi64(_mm512_loadu_si512(ancestors + j + 8), vbase);
    // Unsigned: a negative offset is out of the window too.
    if ((_mm512_cmplt_epu64_mask(lo, window) & _mm512_cmplt_epu64_mask(hi, window)) != 0xff) {
      return false;
    }
    const __m512i index = _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvtepi64_epi32(lo)),
                                             _mm512_cvtepi64_epi32(hi), 1);
    for (int c = 0; c < Cols; ++c) {
      const T* s = from[c] + base;
      _mm512_storeu_ps(to[c] + j, _mm512_permutex2var_ps(_mm512_loadu_ps(s), index,
                                                         _mm512_loadu_ps(s + 16)));
    }
  } else {
    const __m512i index = _mm512_sub_epi64(_mm512_loadu_si512(ancestors + j), vbase);
    if (_mm512_cmplt_epu64_mask(index, window) != 0xff) return false;
    for (int c = 0; c < Cols; ++c) {
      const T* s = from[c] + base;
      _mm512_storeu_pd(to[c] + j, _mm512_permutex2var_pd(_mm512_loadu_pd(s), index,
                                                         _mm512_loadu_pd(s + 8)));
    }
  }
  return true;
}
#endif

// Columns [0, Cols) of src (rows src_stride apart) to dst, rows [0, n) of the ancestors.
template <int Cols, typename T>
void columns(const T* src, Eigen::Index src_stride, Eigen::Index src_rows,
             const std::int64_t* ancestors, Eigen::Index n, T* dst, Eigen::Index dst_stride) {
  const T* from[Cols];
  T* to[Cols];
  for (int c = 0; c < Cols; ++c) {
    from[c] = src + c * src_stride;
    to[c] = dst + c * dst_stride;
  }
  Eigen::Index j = 0;
#if defined(__AVX512F__)
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) {
    constexpr Eigen::Index kLanes = 64 / sizeof(T);
    for (; j + kLanes <= n; j += kLanes) {
      if (!permuted_rows<Cols>(from, to, ancestors, j, src_rows)) {
        scalar_rows<Cols>(from, to, ancestors, j, j + kLanes);
      }
    }
  }
#else
  (void)src_rows;
#endif
  scalar_rows<Cols>(from, to, ancestors, j, n);
}

}  // namespace gather_detail

// dst(j, c) <- src(ancestors[j], c) for j < n and every column c < cols; src has src_rows rows
// per column (src_stride apart), dst's columns are dst_stride apart. Any ancestors in
// [0, src_rows); sorted ones are fastest.
template <typename T>
void gather_block(const T* src, Eigen::Index src_stride, Eigen::Index src_rows, Eigen::Index cols,
                  const std::int64_t* ancestors, Eigen::Index n, T* dst, Eigen::Index dst_stride) {
  using gather_detail::columns;
  Eigen::Index c = 0;
  for (; c + 4 <= cols; c += 4) {
    columns<4>(src + c * src_stride, src_stride, src_rows, ancestors, n, dst + c * dst_stride,
               dst_stride);
  }
  const T* from = src + c * src_stride;
  T* to = dst + c * dst_stride;
  switch (cols - c) {
    case 3: columns<3>(from, src_stride, src_rows, ancestors, n, to, dst_stride); break;
    case 2: columns<2>(from, src_stride, src_rows, ancestors, n, to, dst_stride); break;
    case 1: columns<1>(from, src_stride, src_rows, ancestors, n, to, dst_stride); break;
    default: break;
  }
}

}  // namespace vtrack::smc

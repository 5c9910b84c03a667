#include "vtrack/image/components.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "vtrack/core/errors.hpp"

namespace vtrack::image {

namespace {

// A horizontal run of foreground pixels: columns first..last (inclusive) of one row.
struct Run {
  int row, first, last;
};

// Appends the runs of one mask row. Zero bytes are skipped eight at a time: a background
// subtraction mask is mostly zeros.
void append_runs(const uchar* m, int cols, int row, std::vector<Run>& runs) {
  int c = 0;
  while (c < cols) {
    while (c + 8 <= cols) {
      std::uint64_t word;
      std::memcpy(&word, m + c, sizeof word);
      if (word != 0) break;
      c += 8;
    }
    while (c < cols && !m[c]) ++c;
    if (c == cols) break;
    const int first = c;
    while (c < cols && m[c]) ++c;
    runs.push_back({row, first, c - 1});
  }
}

// The root of a run's set, halving the path on the way (the roots stay the smallest index).
int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    const int up = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    parent[static_cast<std::size_t>(i)] = up;
    i = up;
  }
  return i;
}

// Joins two sets; the smaller index becomes the root, so a set's root is its first run in raster
// order, the run holding the component's first pixel.
void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a < b) {
    parent[static_cast<std::size_t>(b)] = a;
  } else if (b < a) {
    parent[static_cast<std::size_t>(a)] = b;
  }
}

}  // namespace

int connected_components(const cv::Mat& mask, cv::Mat& stats) {
  if (mask.empty() || mask.type() != CV_8UC1) {
    throw InvalidArgument("mask must be a non-empty CV_8UC1 image");
  }
  std::vector<Run> runs;
  std::vector<int> parent;
  std::size_t above = 0;  // the previous row's runs are runs[above, row_start)
  for (int r = 0; r < mask.rows; ++r) {
    const std::size_t row_start = runs.size();
    append_runs(mask.ptr<uchar>(r), mask.cols, r, runs);
    for (std::size_t i = row_start; i < runs.size(); ++i) {
      parent.push_back(static_cast<int>(i));
      // 8-connectivity: a run above touches this one when their column spans, each widened by
      // one pixel, overlap. Both rows' runs are sorted, so the scan of the row above resumes.
      while (above < row_start && runs[above].last + 1 < runs[i].first) ++above;
      for (std::size_t j = above; j < row_start && runs[j].first <= runs[i].last + 1; ++j) {
        unite(parent, static_cast<int>(i), static_cast<int>(j));
      }
    }
    above = row_start;
  }
  // Number the roots in raster order, then gather every run into its component's box and area.
  std::vector<int> component(runs.size(), 0);
  int n = 1;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int root = find_root(parent, static_cast<int>(i));
    component[i] = root == static_cast<int>(i) ? n++ : component[static_cast<std::size_t>(root)];
  }
  stats.create(n, cv::CC_STAT_MAX, CV_32S);
  stats.setTo(0);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Run& run = runs[i];
    int* s = stats.ptr<int>(component[i]);
    const bool first_run = s[cv::CC_STAT_AREA] == 0;
    // Boxes as (left, top, right, bottom) while gathering, then as OpenCV's width and height.
    s[cv::CC_STAT_LEFT] = first_run ? run.first : std::min(s[cv::CC_STAT_LEFT], run.first);
    s[cv::CC_STAT_WIDTH] = first_run ? run.last : std::max(s[cv::CC_STAT_WIDTH], run.last);
    if (first_run) s[cv::CC_STAT_TOP] = run.row;  // runs come in raster order
    s[cv::CC_STAT_HEIGHT] = run.row;
    s[cv::CC_STAT_AREA] += run.last - run.first + 1;
  }
  for (int i = 1; i < n; ++i) {
    int* s = stats.ptr<int>(i);
    s[cv::CC_STAT_WIDTH] -= s[cv::CC_STAT_LEFT] - 1;
    s[cv::CC_STAT_HEIGHT] -= s[cv::CC_STAT_TOP] - 1;
  }
  return n;
}

}  // namespace vtrack::image

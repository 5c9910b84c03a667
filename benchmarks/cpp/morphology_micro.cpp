// Micro-benchmark of image::close_square (the closing of the KDE background model and of the MB
// likelihood) against OpenCV's cv::morphologyEx(MORPH_CLOSE) with a square kernel, both on one
// thread, on a 768 x 576 float image of uniform noise (a max/min filter's cost does not depend
// on the values). Process CPU time per closing, median of 200 runs, per size.
//
// Build against the library of a `make build` and run, on one line:
//   g++ -std=c++17 -O3 -march=native -Icpp/include -isystem /usr/include/opencv4
//       benchmarks/cpp/morphology_micro.cpp build/wheel/libvtrack.a -lopencv_imgproc
//       -lopencv_core -o build/morphology_micro && build/morphology_micro
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "vtrack/image/morphology.hpp"

namespace {

double process_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

template <class F>
double median_us(F f) {
  std::vector<double> t;
  for (int r = 0; r < 200; ++r) {
    const double start = process_cpu_us();
    f();
    t.push_back(process_cpu_us() - start);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main() {
  cv::setNumThreads(1);
  cv::Mat src(576, 768, CV_32FC1), ours, theirs, workspace;
  cv::RNG(3).fill(src, cv::RNG::UNIFORM, 0.0f, 1.0f);
  std::printf("size  vtrack close_square (us)  cv::morphologyEx (us)  ratio  equal\n");
  for (const int size : {3, 5, 7, 9, 13}) {
    const cv::Mat kernel = cv::Mat::ones(size, size, CV_8U);
    const double a = median_us([&] { vtrack::image::close_square(src, ours, size, 1, &workspace); });
    const double b = median_us([&] { cv::morphologyEx(src, theirs, cv::MORPH_CLOSE, kernel); });
    std::printf("%4d  %24.1f  %21.1f  %5.2f  %s\n", size, a, b, b / a,
                cv::norm(ours, theirs, cv::NORM_INF) == 0.0 ? "yes" : "NO");
  }
  return 0;
}

// Micro-benchmark of the colour particle filter's update (filters/color_particle.hpp) split by
// stage, on real frames: PETS09-S2L1 person 15 from frame 1 (its MOTChallenge GT box), followed
// for 150 frames, then the same frames' particle clouds scored again stage by stage. One thread,
// its CPU time, medians over frames (microseconds per update). benchmarks/follow.py has the
// figures and what they led to. The stages score the clouds the filter held after each update,
// i.e. resampled (copies of a box cost nothing), on a frame already in cache: they understate
// the update's own quantising (its frame comes cold from memory) and scoring.
//
// AMD EPYC (Zen 5, AVX-512), loaded, medians of 3 alternating runs, main -> issue 11's second
// speed session (benchmarks/follow.py): update at N = 30 / 90 / 210, kernel 83.3 / 162.5 / 324.5
// -> 43.4 / 86.6 / 181.2 us, unweighted (kernel 0) 50.1 / 113.1 / 205.4 -> 27.8 / 64.9 / 120.0
// us; at N = 30, kernel: quantise 15.8 -> 4.3 us (1.23 -> 0.33 ns/px), score 33.8 -> 22.0 us.
//
// Build against the library of a `make build` (same flags as the library) and run, on one line:
//   g++ -std=c++17 -O3 -march=native -fno-trapping-math -fno-math-errno -Icpp/include
//       -isystem /usr/include/eigen3 -isystem /usr/include/opencv4 benchmarks/cpp/color_micro.cpp
//       build/wheel/libvtrack.a -lopencv_videoio -lopencv_imgproc -lopencv_core
//       -o build/color_micro && build/color_micro ~/.cache/vtrack/vtest.avi [N] [kernel 0|1]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include <time.h>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "vtrack/filters/color_particle.hpp"
#include "vtrack/image/color_histogram.hpp"

using namespace vtrack;

namespace {

// The calling thread's CPU time (as benchmarks/follow.py's time.thread_time).
double cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Median over `repeats` runs of f() in microseconds.
template <class F>
double time_us(F f, int repeats = 15) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double start = cpu_us();
    f();
    t.push_back(cpu_us() - start);
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s VIDEO [N] [kernel 0|1]\n", argv[0]);
    return 2;
  }
  const int n = argc > 2 ? std::atoi(argv[2]) : 30;
  const bool kernel = argc > 3 ? std::atoi(argv[3]) != 0 : true;
  cv::VideoCapture cap(argv[1]);
  std::vector<cv::Mat> frames;
  for (cv::Mat f; frames.size() < 151 && cap.read(f);) frames.push_back(f.clone());
  if (frames.size() < 151) {
    std::fprintf(stderr, "cannot decode 151 frames of %s\n", argv[1]);
    return 1;
  }
  filters::ColorParticleParams params;
  params.n_particles = n;
  params.color.histogram.kernel = kernel;
  filters::ColorParticleFilter pf(params);
  pf.init(frames[0], filters::Box{258, 219, 32.913, 88.702});  // gt.txt: frame 1, id 15
  std::vector<double> update, quantise, score, region;
  std::vector<std::vector<double>> clouds;
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const double start = cpu_us();
    pf.update(frames[k]);
    update.push_back(cpu_us() - start);
    const Eigen::MatrixXd b = pf.particle_boxes();
    std::vector<double> boxes(static_cast<std::size_t>(4 * b.rows()));
    for (Eigen::Index i = 0; i < b.rows(); ++i) {
      for (int c = 0; c < 4; ++c) boxes[static_cast<std::size_t>(4 * i + c)] = b(i, c);
    }
    clouds.push_back(boxes);
  }
  // The stages on the clouds the filter held after each update (scored on the next frame).
  image::HsvBinImage bins(params.color.histogram);
  const image::ColorModel model(params.color.histogram, pf.reference());
  std::vector<double> rho(static_cast<std::size_t>(n));
  for (std::size_t k = 1; k + 1 < frames.size(); ++k) {
    const cv::Mat& frame = frames[k + 1];
    const std::vector<double>& boxes = clouds[k - 1];
    const image::Rect roi = image::boxes_roi(boxes.data(), static_cast<std::size_t>(n), 4,
                                             frame.cols, frame.rows);
    region.push_back(static_cast<double>(roi.width) * roi.height);
    quantise.push_back(time_us([&] { bins.assign(frame, roi); }));
    score.push_back(time_us([&] {
      model.coefficients(bins, boxes.data(), static_cast<std::size_t>(n), 4, rho.data());
    }));
  }
  std::printf("N = %d, kernel %d: update %.1f us (median over %zu frames); quantise %.1f us "
              "(region %.0f px, %.2f ns/px), score %.1f us\n",
              n, kernel ? 1 : 0, median(update), update.size(), median(quantise), median(region),
              1e3 * median(quantise) / median(region), median(score));
  return 0;
}

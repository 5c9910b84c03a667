// Micro-benchmark of image::connected_components (the person-size estimator's labelling) against
// OpenCV's cv::connectedComponents and cv::connectedComponentsWithStats, on real foreground
// masks: OpenCV's MOG2 foreground of PETS09-S2L1 (shadows dropped), frames 50-249, at the video's
// size. Reported per mask, medians over the masks: process CPU time (OpenCV's pool threads
// count) and wall time, with OpenCV's default threads and with cv::setNumThreads(1).
//
// Build against the library of a `make build` and run, on one line:
//   g++ -std=c++17 -O3 -march=native -Icpp/include -isystem /usr/include/opencv4
//       benchmarks/cpp/components_micro.cpp build/wheel/libvtrack.a -lopencv_video
//       -lopencv_videoio -lopencv_imgproc -lopencv_core -o build/components_micro
//       && build/components_micro ~/.cache/vtrack/vtest.avi
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>
#include <opencv2/videoio.hpp>

#include "vtrack/image/components.hpp"

namespace {

double process_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double wall_us() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double, std::micro>(clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Medians over the masks of f(mask)'s process CPU and wall time (each mask timed 5 times, its
// median kept).
template <class F>
void report(const char* name, const std::vector<cv::Mat>& masks, F f) {
  std::vector<double> cpu, wall;
  for (const cv::Mat& mask : masks) {
    std::vector<double> c, w;
    for (int r = 0; r < 5; ++r) {
      const double c0 = process_cpu_us(), w0 = wall_us();
      f(mask);
      c.push_back(process_cpu_us() - c0);
      w.push_back(wall_us() - w0);
    }
    cpu.push_back(median(c));
    wall.push_back(median(w));
  }
  std::printf("%-44s %9.1f %9.1f\n", name, median(cpu), median(wall));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s VIDEO\n", argv[0]);
    return 2;
  }
  cv::VideoCapture video(argv[1], cv::CAP_FFMPEG);
  if (!video.isOpened()) {
    std::fprintf(stderr, "cannot open %s\n", argv[1]);
    return 1;
  }
  cv::Ptr<cv::BackgroundSubtractorMOG2> mog2 = cv::createBackgroundSubtractorMOG2();
  std::vector<cv::Mat> masks;
  cv::Mat frame, foreground;
  for (int f = 0; f < 250 && video.read(frame); ++f) {
    mog2->apply(frame, foreground);
    if (f >= 50) masks.push_back(foreground == 255);
  }
  std::printf("%zu masks of %d x %d; us per mask, medians: process CPU, wall\n", masks.size(),
              masks.empty() ? 0 : masks[0].cols, masks.empty() ? 0 : masks[0].rows);
  cv::Mat labels, stats, centroids;
  for (const int threads : {cv::getNumThreads(), 1}) {
    cv::setNumThreads(threads);
    std::printf("OpenCV threads: %d\n", cv::getNumThreads());
    report("  vtrack image::connected_components", masks,
           [&](const cv::Mat& m) { vtrack::image::connected_components(m, stats); });
    report("  cv::connectedComponents", masks,
           [&](const cv::Mat& m) { cv::connectedComponents(m, labels, 8, CV_32S); });
    report("  cv::connectedComponentsWithStats", masks, [&](const cv::Mat& m) {
      cv::connectedComponentsWithStats(m, labels, stats, centroids, 8, CV_32S);
    });
  }
  return 0;
}

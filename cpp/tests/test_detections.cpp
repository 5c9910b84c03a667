// MOTChallenge detection files, the box GLMB tracker of apps/track_detections and the HOG detector.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <Eigen/LU>
#include <opencv2/imgproc.hpp>

#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/core/errors.hpp"

#include <unistd.h>

namespace {

using vtrack::apps::BoxTrackerParams;
using vtrack::apps::Detection;

class DetectionFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    // The process id: ctest runs the tests of this fixture in parallel processes, which share
    // gtest's time-based random seed (one test's TearDown removed another's files).
    const auto path = std::filesystem::temp_directory_path() /
                      ("vtrack_det_" + std::to_string(::getpid()) + "_" +
                       std::to_string(counter_++) + ".txt");
    std::ofstream(path) << text;
    paths_.push_back(path);
    return path.string();
  }
  // The InvalidArgument message of reading `text`, or "" if it reads.
  std::string error_of(const std::string& text, std::string* path_out = nullptr) {
    const std::string path = write(text);
    if (path_out) *path_out = path;
    try {
      vtrack::apps::read_detections(path);
    } catch (const vtrack::InvalidArgument& e) {
      return e.what();
    }
    return "";
  }
  void TearDown() override {
    for (const auto& p : paths_) std::filesystem::remove(p);
  }

 private:
  std::vector<std::filesystem::path> paths_;
  int counter_ = 0;
};

TEST_F(DetectionFile, ReadsRowsWithAndWithoutConfidenceAndSkipsBlankLines) {
  const auto dets = vtrack::apps::read_detections(
      write("1,-1,10,20,30,40,0.9,-1,-1,-1\n\n2,-1,1.5,2.5,3.5,4.5\n 3 , 7 ,0,0,1,1,0.2\n"));
  ASSERT_EQ(dets.size(), 3u);
  EXPECT_EQ(dets[0].frame, 1);
  EXPECT_DOUBLE_EQ(dets[0].x, 10);
  EXPECT_DOUBLE_EQ(dets[0].h, 40);
  EXPECT_DOUBLE_EQ(dets[0].confidence, 0.9);
  EXPECT_DOUBLE_EQ(dets[1].w, 3.5);
  EXPECT_DOUBLE_EQ(dets[1].confidence, 1.0);  // no conf column
  EXPECT_EQ(dets[2].frame, 3);
  // The confidence filter keeps conf >= min_confidence.
  const auto path = write("1,-1,0,0,1,1,0.5\n1,-1,0,0,1,1,0.7\n2,-1,0,0,1,1,0.69\n");
  EXPECT_EQ(vtrack::apps::read_detections(path, 0.7).size(), 1u);
  EXPECT_TRUE(vtrack::apps::read_detections(write("")).empty());
}

TEST_F(DetectionFile, ErrorsNameTheFileAndLine) {
  std::string path;
  const std::pair<std::string, std::string> cases[] = {
      {"1,-1,0,0,1,1\n2,-1,a,0,1,1\n", ":2: x is not a number: 'a'"},
      {"1,-1,0,0,1\n", ":1: expected 6 to 10 comma-separated fields"},
      {"1,-1,0,0,1,1,1,1,1,1,1\n", ":1: expected 6 to 10"},
      {"\n\n1,-1,nan,0,1,1\n", ":3: x must be finite"},
      {"1,-1,0,0,1,inf\n", ":1: h must be finite"},
      {"1,-1,0,0,1,1,nan\n", ":1: conf must be finite"},
      {"1,-1,0,0,0,1\n", ":1: w must be > 0, got 0"},
      {"1,-1,0,0,1,-2\n", ":1: h must be > 0, got -2"},
      {"0,-1,0,0,1,1\n", ":1: frame must be >= 1"},
      {"1.5,-1,0,0,1,1\n", ":1: frame must be an integer, got '1.5'"},
      {"1,-1,0,,1,1\n", ":1: y is not a number: ''"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = error_of(text, &path);
    EXPECT_NE(message.find(path + expected), std::string::npos) << text << " -> " << message;
  }
  EXPECT_THROW(vtrack::apps::read_detections("/no/such/det.txt"), vtrack::IoError);
}

TEST_F(DetectionFile, WriteThenReadIsTheSameAndLeavesNoPartialFile) {
  const std::vector<Detection> dets = {{1, 1.25, 2.5, 30, 40, 0.75}, {4, 5, 6, 7, 8, 1}};
  const auto path = (std::filesystem::temp_directory_path() / "vtrack_written_det.txt").string();
  vtrack::apps::write_detections(path, dets);
  const auto back = vtrack::apps::read_detections(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].frame, 4);
  EXPECT_DOUBLE_EQ(back[0].x, 1.25);
  EXPECT_DOUBLE_EQ(back[0].confidence, 0.75);
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::temp_directory_path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_FALSE(name.rfind("vtrack_written_det.txt.", 0) == 0) << name;  // no temporary left
  }
  std::filesystem::remove(path);
}

// One target moving at constant velocity, detected every frame without clutter (p_D -> 1, tiny
// clutter rate): the GLMB's single track must be the Kalman filter in closed form, started from the
// adaptive birth density N([z1 centre, 0, z1 size], diag(birth_sd^2)) at frame 2 (the detection of
// frame 1 proposes the birth, GlmbParams::adaptive_birth) and updated with z2, z3, ...
TEST(BoxTracker, SingleTargetEqualsTheKalmanFilter) {
  BoxTrackerParams p;
  p.detection_probability = 1 - 1e-9;
  p.clutter_rate = 1e-6;
  p.birth_max_existence = 0.9;
  // Fixed p_D and clutter, constant noise, no runs of misses, no duplicates: the textbook model.
  p.learn_detection_probability = false;
  p.learn_clutter = false;
  p.use_scores = false;
  p.duplicate_rate = 0;
  p.detection_sd_relative = 0;
  p.occlusion.rate = 0;
  // The model written out independently of box_motion/box_observation and models/: state
  // [cx, vcx, cy, vcy, w, h], F = I2 (x) [[1, 1], [0, 1]] plus identity for the size, Q = sigma_a^2
  // I2 (x) g g^T with g = [1/2, 1] plus sigma_s^2 for the size (eq. 7, T = 1); z = (cx, cy, w, h).
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(6, 6), Q = Eigen::MatrixXd::Zero(6, 6);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, 6), R = Eigen::MatrixXd::Zero(4, 4);
  const double a2 = p.sigma_accel * p.sigma_accel;
  for (int axis = 0; axis < 2; ++axis) {
    const int i = 2 * axis;
    F(i, i + 1) = 1;
    Q(i, i) = a2 / 4;
    Q(i, i + 1) = Q(i + 1, i) = a2 / 2;
    Q(i + 1, i + 1) = a2;
  }
  Q(4, 4) = Q(5, 5) = p.sigma_size * p.sigma_size;
  H(0, 0) = H(1, 2) = H(2, 4) = H(3, 5) = 1;
  R.diagonal() << std::pow(p.detection_sd_centre, 2), std::pow(p.detection_sd_centre, 2),
      std::pow(p.detection_sd_size, 2), std::pow(p.detection_sd_size, 2);
  vtrack::apps::BoxTracker tracker(640, 480, p);
  std::vector<Eigen::Vector4d> z;  // (cx, cy, w, h), wobbling around a straight walk
  for (int k = 0; k < 30; ++k) {
    z.emplace_back(100 + 3.0 * k + 2 * std::sin(k), 200 - 1.5 * k + 2 * std::cos(1.3 * k),
                   40 + std::sin(0.7 * k), 100 + 2 * std::cos(0.4 * k));
  }
  Eigen::VectorXd m(6);
  Eigen::MatrixXd P(6, 6);
  for (int k = 0; k < 30; ++k) {
    const Detection d{k + 1, z[k][0] - z[k][2] / 2, z[k][1] - z[k][3] / 2, z[k][2], z[k][3], 1};
    const auto tracks = tracker.step({d});
    if (k == 0) {
      EXPECT_TRUE(tracks.empty());  // births come from the previous frame's detections
      m << z[0][0], 0, z[0][1], 0, z[0][2], z[0][3];
      Eigen::VectorXd sd(6);
      sd << p.birth_sd_centre, p.birth_sd_velocity, p.birth_sd_centre, p.birth_sd_velocity,
          p.birth_sd_size, p.birth_sd_size;
      P = sd.array().square().matrix().asDiagonal();
      continue;
    }
    if (k > 1) {
      m = F * m;
      P = F * P * F.transpose() + Q;
    }
    const Eigen::MatrixXd K = P * H.transpose() * (H * P * H.transpose() + R).inverse();
    m += K * (Eigen::VectorXd(z[k]) - H * m);
    P = (Eigen::MatrixXd::Identity(6, 6) - K * H) * P;
    ASSERT_EQ(tracks.size(), 1u) << "frame " << k + 1;
    EXPECT_EQ(tracks[0].id, 1u);
    EXPECT_NEAR(tracks[0].x + tracks[0].w / 2, m[0], 1e-6) << "frame " << k + 1;
    EXPECT_NEAR(tracks[0].y + tracks[0].h / 2, m[2], 1e-6);
    EXPECT_NEAR(tracks[0].w, m[4], 1e-6);
    EXPECT_NEAR(tracks[0].h, m[5], 1e-6);
  }
}

TEST(BoxTracker, RowsCoverEveryFrameAndIdsFollowFirstAppearance) {
  // Two targets far apart; the second appears at frame 6. Frames after the last detection (up to
  // last_frame) are still run, and get rows while the tracks survive.
  std::vector<Detection> dets;
  for (int f = 1; f <= 12; ++f) {
    dets.push_back({f, 100.0 + f, 100, 40, 100, 1});
    if (f >= 6) dets.push_back({f, 400.0 - f, 200, 40, 100, 1});
  }
  const auto rows = vtrack::apps::track_detections(dets, 640, 480, {}, 15);
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.front().frame, 2);
  // A missed frame or two does not end a track (p_D = 0.9), so frames 13-14 still have rows.
  EXPECT_GT(rows.back().frame, 12);
  EXPECT_LE(rows.back().frame, 15);
  std::uint64_t max_id = 0;
  for (const auto& r : rows) {
    EXPECT_LE(r.id, max_id + 1) << "ids must appear in order";
    max_id = std::max(max_id, r.id);
    if (r.frame >= 8 && r.frame <= 12) {
      EXPECT_EQ(r.id, r.x < 250 ? 1u : 2u);
    }
  }
  EXPECT_EQ(max_id, 2u);
  // Same input, same rows.
  const auto again = vtrack::apps::track_detections(dets, 640, 480, {}, 15);
  ASSERT_EQ(again.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(again[i].x, rows[i].x);
}

TEST(BoxTracker, BadParametersAndInputsAreNamed) {
  BoxTrackerParams p;
  p.detection_probability = 1.0;
  EXPECT_THROW(vtrack::apps::validate(p), vtrack::InvalidArgument);
  p = {};
  p.hypothesis_budget = 0;
  try {
    vtrack::apps::validate(p);
    FAIL();
  } catch (const vtrack::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("hypothesis_budget"), std::string::npos);
  }
  EXPECT_THROW(vtrack::apps::BoxTracker(0, 480), vtrack::InvalidArgument);
  const std::vector<Detection> bad = {{1, 0, 0, -1, 10, 1}};
  EXPECT_THROW(vtrack::apps::track_detections(bad, 640, 480), vtrack::InvalidArgument);
}

TEST(HogDetector, FindsNothingOnABlankFrameAndRejectsBadInput) {
  const vtrack::apps::HogPeopleDetector detector;
  EXPECT_TRUE(detector.detect(cv::Mat(240, 320, CV_8UC3, cv::Scalar(128, 128, 128))).empty());
  EXPECT_THROW(detector.detect(cv::Mat()), vtrack::InvalidArgument);
  EXPECT_THROW(detector.detect(cv::Mat(64, 64, CV_32FC3)), vtrack::InvalidArgument);
  vtrack::apps::HogParams p;
  p.win_stride = 5;
  EXPECT_THROW(vtrack::apps::HogPeopleDetector{p}, vtrack::InvalidArgument);
}

}  // namespace

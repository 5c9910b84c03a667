// Issue 16's guarantees at the C++ level: interruption of long loops, temporary files a signal
// handler can remove, outputs checked before any work, covariances and sizes checked before
// use, hostile text files refused before parsing, and the box tracker's cost independent of the
// frame numbers (with the same rows as stepping through every frame).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "scratch_dir.hpp"
#include "vtrack/apps/config.hpp"
#include "vtrack/apps/hog_detector.hpp"
#include "vtrack/apps/mot_files.hpp"
#include "vtrack/apps/output_paths.hpp"
#include "vtrack/apps/temporary_files.hpp"
#include "vtrack/apps/track_detections.hpp"
#include "vtrack/apps/video_writer.hpp"
#include "vtrack/core/errors.hpp"
#include "vtrack/core/gaussian.hpp"
#include "vtrack/core/interrupt.hpp"
#include "vtrack/core/text_file.hpp"
#include "vtrack/filters/glmb_tracker.hpp"

namespace {

namespace fs = std::filesystem;
using vtrack::apps::BoxTrackerParams;
using vtrack::apps::Detection;
using vtrack::apps::TrackRow;

// A fresh folder under the system temp folder, removed with the fixture.
class Scratch : public ScratchDirTest {
 protected:
  std::string file(const std::string& name, const std::string& text = "") {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
};

struct Stop {};

TEST(Interrupt, ChecksNestAndStopLongLoops) {
  vtrack::core::poll_interrupt();  // no check installed: nothing happens
  int outer = 0, inner = 0;
  {
    const vtrack::core::InterruptScope a([&] { ++outer; });
    vtrack::core::poll_interrupt();
    {
      const vtrack::core::InterruptScope b([&] { ++inner; });
      vtrack::core::poll_interrupt();
      const vtrack::core::InterruptScope empty({});  // keeps b
      vtrack::core::poll_interrupt();
    }
    vtrack::core::poll_interrupt();
  }
  vtrack::core::poll_interrupt();
  EXPECT_EQ(outer, 2);
  EXPECT_EQ(inner, 2);

  // A check that throws stops track_detections between frames, with the exception it threw.
  std::vector<Detection> dets;
  for (long long f = 1; f <= 50; ++f) dets.push_back({f, 100.0 + f, 100, 40, 100, 0.9});
  int polls = 0;
  const vtrack::core::InterruptScope stop([&] {
    if (++polls == 10) throw Stop{};
  });
  EXPECT_THROW(vtrack::apps::track_detections(dets, 640, 480), Stop);
  EXPECT_EQ(polls, 10);
}

TEST_F(Scratch, RegisteredTemporaryFilesAreRemovedOnRequestOnly) {
  const std::string a = file("a.partial", "x"), b = file("b.partial", "y");
  {
    vtrack::apps::TemporaryFile ra(a), rb(b);
    rb.release();
    EXPECT_GE(vtrack::apps::remove_temporary_files(), 1);
  }
  EXPECT_FALSE(fs::exists(a));
  EXPECT_TRUE(fs::exists(b));  // released: not ours to remove any more
  EXPECT_EQ(vtrack::apps::remove_temporary_files(), 0);  // deregistered on destruction

  // A video being written is registered under its temporary name until committed.
  const std::string video = (dir_ / "out.avi").string();
  vtrack::apps::AtomicVideoWriter writer(video, 10, cv::Size(32, 24));
  writer.write(cv::Mat(24, 32, CV_8UC3, cv::Scalar(1, 2, 3)));
  const auto partial_videos = [&] {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("out.", 0) == 0 && name.size() > 12 &&
          name.compare(name.size() - 12, 12, ".partial.avi") == 0) {
        found.push_back(name);
      }
    }
    return found;
  };
  EXPECT_EQ(partial_videos().size(), 1u);
  vtrack::apps::remove_temporary_files();  // what the CLI's second-signal handler does
  EXPECT_TRUE(partial_videos().empty());
  EXPECT_FALSE(fs::exists(video));
}

TEST(TemporaryFiles, EveryWriteGetsItsOwnName) {
  namespace apps = vtrack::apps;
  const fs::path target = fs::path("dir") / "tracks.txt";
  const fs::path a = apps::partial_path(target), b = apps::partial_path(target);
  EXPECT_NE(a, b);  // two writers of one target never share a temporary file
  EXPECT_EQ(a.parent_path(), target.parent_path());
  EXPECT_EQ(a.filename().string().rfind("tracks.txt.", 0), 0u);
  EXPECT_EQ(a.extension(), ".partial");
  const fs::path video = apps::partial_path(fs::path("out.mp4"), /*keep_extension=*/true);
  EXPECT_EQ(video.extension(), ".mp4");  // FFmpeg picks the container from it
  EXPECT_EQ(video.stem().extension(), ".partial");
}

TEST_F(Scratch, OutputsAreCheckedAgainstInputsAndEachOther) {
  using vtrack::apps::check_outputs;
  const std::string video = file("in.avi", "not really a video");
  const std::string link = (dir_ / "link.avi").string();
  fs::create_symlink(video, link);
  const auto message = [&](const std::vector<vtrack::apps::NamedPath>& outputs) -> std::string {
    try {
      check_outputs({{"VIDEO", video}, {"--config", ""}}, outputs);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message({{"--out", (dir_ / "t.txt").string()}}), "");
  EXPECT_NE(message({{"--out", video}}).find("--out '" + video + "' is the input VIDEO"),
            std::string::npos);
  // The same file through a link, "." and "..".
  EXPECT_NE(message({{"--render", link}}).find("is the input VIDEO"), std::string::npos);
  const std::string dotted = (dir_ / "." / ".." / dir_.filename() / "in.avi").string();
  EXPECT_NE(message({{"--render", dotted}}).find("is the input VIDEO"), std::string::npos);
  // Two outputs on one path (neither exists yet).
  EXPECT_NE(message({{"--out", (dir_ / "t.txt").string()},
                     {"--save-detections", (dir_ / "./t.txt").string()}})
                .find("--save-detections '" + (dir_ / "./t.txt").string() + "' is also --out"),
            std::string::npos);
  // A file output that is a folder, a folder output that is a file.
  EXPECT_NE(message({{"--out", dir_.string()}}).find("is a folder"), std::string::npos);
  EXPECT_NE(message({{"--out", video, true}}).find("not a folder"), std::string::npos);
  // A missing folder is an IoError; a folder output may create its missing parents.
  EXPECT_THROW(check_outputs({}, {{"--out", (dir_ / "nope" / "t.txt").string()}}), vtrack::IoError);
  EXPECT_NO_THROW(check_outputs({}, {{"--out", (dir_ / "a" / "b").string(), true}}));
  EXPECT_THROW(check_outputs({}, {{"--out", ""}}), vtrack::InvalidArgument);
}

TEST(Covariances, AreCheckedBeforeUse) {
  using vtrack::core::require_covariance;
  EXPECT_NO_THROW(require_covariance(Eigen::Matrix2d::Identity(), "R", true));
  Eigen::Matrix2d singular;
  singular << 1, 1, 1, 1;
  EXPECT_NO_THROW(require_covariance(singular, "Q", false));
  EXPECT_THROW(require_covariance(singular, "R", true), vtrack::InvalidArgument);
  Eigen::Matrix2d indefinite;
  indefinite << 1, 2, 2, 1;  // eigenvalues 3 and -1
  try {
    require_covariance(indefinite, "motion Q", false);
    FAIL() << "an indefinite Q was accepted";
  } catch (const vtrack::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("motion Q must be positive semi-definite, has eigenvalue -1"),
              std::string::npos) << e.what();
  }
  Eigen::Matrix2d asymmetric;
  asymmetric << 1, 0.5, 0, 1;
  EXPECT_THROW(require_covariance(asymmetric, "cov", false), vtrack::InvalidArgument);
  EXPECT_THROW(require_covariance(Eigen::Matrix2d::Constant(NAN), "cov", false),
               vtrack::InvalidArgument);
  EXPECT_THROW(require_covariance(Eigen::Matrix3d::Identity(), "cov", false, 2),
               vtrack::InvalidArgument);

  // The GLMB tracker refuses a negative-definite Q at construction instead of returning
  // negative variances later.
  auto motion = vtrack::models::LinearGaussianMotion::constant_velocity(2, 1.0, 1.0);
  const auto observation = vtrack::models::LinearGaussianObservation::position_of_constant_velocity(
      2, Eigen::Matrix2d::Identity());
  motion.Q = -0.5 * Eigen::Matrix4d::Identity();
  EXPECT_THROW(vtrack::filters::GlmbTracker(motion, observation, {}), vtrack::InvalidArgument);
  motion.Q = Eigen::Matrix4d::Identity();
  std::vector<vtrack::filters::GaussianBirth> births(1);
  births[0].density = {Eigen::Vector4d::Zero(), -Eigen::Matrix4d::Identity()};
  EXPECT_THROW(vtrack::filters::GlmbTracker(motion, observation, births), vtrack::InvalidArgument);
}

TEST_F(Scratch, TextFilesAreRefusedBeforeTheParserSeesThem) {
  using vtrack::core::read_text_file;
  EXPECT_EQ(read_text_file(file("ok.yml", "a: [1, {b: 2}]\n"), "config file", 100, 2),
            "a: [1, {b: 2}]\n");
  EXPECT_THROW(read_text_file(dir_.string(), "config file", 100), vtrack::IoError);
  EXPECT_THROW(read_text_file("/dev/zero", "config file", 100), vtrack::IoError);  // never ends
  EXPECT_THROW(read_text_file(file("big.yml", std::string(101, 'a')), "config file", 100),
               vtrack::IoError);
  EXPECT_THROW(read_text_file(file("deep.yml", "a: [[[1]]]\n"), "config file", 100, 2),
               vtrack::IoError);
  EXPECT_EQ(vtrack::core::flow_nesting("a: '[[[' \"{{\\\"\" [x]"), 1);  // quotes do not count

  // A ',' where a block node starts hung yaml-cpp, allocating without end (found by fuzz_config).
  using vtrack::core::stray_comma_line;
  EXPECT_EQ(stray_comma_line(","), 1);
  EXPECT_EQ(stray_comma_line("a: 1\n- 1\n  ,"), 3);
  EXPECT_EQ(stray_comma_line("---\n ,"), 2);
  EXPECT_EQ(stray_comma_line("a: [1\n, 2]\nb: {c: 1\n ,d: 2}\n"), 0);  // inside flow: valid
  EXPECT_EQ(stray_comma_line("a: 'x\n,y'\nb: \"1, 2\" # ,\n# ,\n"), 0);  // quoted, comments
  EXPECT_EQ(stray_comma_line("a: 1\nb: &&&,&&\n"), 2);  // after an anchor (found by fuzz_config)
  EXPECT_THROW(vtrack::apps::read_config(file("comma.yml", "seed: 1\n,\n")), vtrack::IoError);
  EXPECT_THROW(vtrack::apps::read_config(file("nul.yml", std::string("\0,", 2))), vtrack::IoError);

  // Not UTF-8 (found by fuzz_config: load_config raised UnicodeDecodeError): named by line.
  using vtrack::core::invalid_utf8_offset;
  EXPECT_EQ(invalid_utf8_offset("a: \xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), std::string::npos);
  EXPECT_EQ(invalid_utf8_offset("ab\xff"), 2u);
  EXPECT_EQ(invalid_utf8_offset("\xc0\xaf"), 0u);          // overlong '/'
  EXPECT_EQ(invalid_utf8_offset("x\xed\xa0\x80"), 1u);    // a UTF-16 surrogate
  EXPECT_EQ(invalid_utf8_offset("x\xe2\x82"), 1u);         // cut short
  try {
    read_text_file(file("bytes.yml", "seed: 1\ntracker: {delta_f: \xff}\n"), "config file", 100);
    ADD_FAILURE() << "a non-UTF-8 file was read";
  } catch (const vtrack::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2 is not UTF-8"), std::string::npos) << e.what();
  }

  // The config reader: block nesting past yaml-cpp's recursion limit, a map as a name, two
  // documents.
  std::string deep;
  for (int i = 0; i < 600; ++i) deep += "- ";
  EXPECT_THROW(vtrack::apps::read_config(file("deep_block.yml", deep + "x\n")), vtrack::IoError);
  EXPECT_THROW(vtrack::apps::read_config(file("key.yml", "tracker: {[a]: 1}\n")),
               vtrack::InvalidArgument);
  EXPECT_THROW(vtrack::apps::read_config(file("two.yml", "seed: 1\n---\nseed: 2\n")),
               vtrack::IoError);
}

TEST_F(Scratch, DetectionRowsAreRangeChecked) {
  const auto error = [&](const std::string& text) -> std::string {
    try {
      vtrack::apps::read_detections(file("d.txt", text));
    } catch (const vtrack::InvalidArgument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error("1,-1,1,1,5,5\n1000000000000000,-1,1,1,5,5\n"), "");
  EXPECT_NE(error("1,-1,1e300,1,5,5\n").find("d.txt:1: x must be within +-1e+09 pixels"),
            std::string::npos);
  EXPECT_NE(error("1,-1,1,1,5,2e9\n").find(":1: h must be within"), std::string::npos);
  EXPECT_NE(error("1e16,-1,1,1,5,5\n").find(":1: frame must be an integer"), std::string::npos);
  // NaN keeps nothing and says nothing: refused.
  EXPECT_THROW(vtrack::apps::read_detections(file("e.txt", "1,-1,1,1,5,5\n"), NAN),
               vtrack::InvalidArgument);
  // An extent beyond any image is refused before it is narrowed to int.
  EXPECT_THROW(vtrack::apps::detections_extent({{1, 9e8, 0, 5e8, 5, 1}}), vtrack::InvalidArgument);
}

// track_detections as it was: one BoxTracker step for every frame 1 .. last.
std::vector<TrackRow> step_every_frame(std::vector<Detection> dets, int w, int h,
                                       const BoxTrackerParams& p, long long last) {
  std::stable_sort(dets.begin(), dets.end(),
                   [](const Detection& a, const Detection& b) { return a.frame < b.frame; });
  for (const auto& d : dets) last = std::max(last, d.frame);
  vtrack::apps::BoxTracker tracker(w, h, p);
  std::vector<TrackRow> rows;
  std::vector<Detection> frame;
  auto next = dets.begin();
  for (long long f = 1; f <= last; ++f) {
    frame.clear();
    for (; next != dets.end() && next->frame == f; ++next) frame.push_back(*next);
    vtrack::apps::append_rows(rows, f, tracker.step(frame));
  }
  return rows;
}

TEST(TrackDetections, SkippingIdleFramesGivesTheRowsOfSteppingEveryFrame) {
  // Bursts of walkers separated by long gaps, clutter, low-confidence boxes; with confirmation,
  // the lost-track memory and Gibbs ranking too.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Detection> dets;
  for (long long start : {1LL, 40LL, 300LL, 310LL}) {
    for (long long f = start; f < start + 15; ++f) {
      if (u(rng) < 0.85) dets.push_back({f, 50.0 + 4 * (f - start), 80, 30, 70, 0.9});
      if (u(rng) < 0.3) dets.push_back({f, 400 * u(rng), 300 * u(rng), 30, 70, u(rng)});
    }
  }
  std::vector<BoxTrackerParams> variants(4);
  variants[1].management = {3, 40, 0.3};
  variants[2].min_confidence = 0.5;
  variants[3].ranking = vtrack::filters::HypothesisRanking::gibbs;
  variants[3].seed = 5;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const auto expected = step_every_frame(dets, 480, 360, variants[v], 400);
    const auto rows = vtrack::apps::track_detections(dets, 480, 360, variants[v], 400);
    ASSERT_FALSE(expected.empty());
    ASSERT_EQ(rows.size(), expected.size()) << "variant " << v;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(rows[i].frame, expected[i].frame) << "variant " << v << " row " << i;
      EXPECT_EQ(rows[i].id, expected[i].id);
      EXPECT_EQ(rows[i].x, expected[i].x);
      EXPECT_EQ(rows[i].confidence, expected[i].confidence);
    }
  }
}

TEST(TrackDetections, CostDoesNotDependOnTheFrameNumbers) {
  // A walker at frames 1-10 and another at 10^14 .. 10^14 + 9, tracked to last_frame 10^15:
  // stepping through the empty frames would take years; the rows of the second walker are
  // those it gets after any gap longer than the idle frames stepped (20 learning memories, 2000
  // frames by default; here 3000 frames), shifted.
  std::vector<Detection> far, near;
  for (long long f = 0; f < 10; ++f) {
    far.push_back({1 + f, 100.0 + 3 * f, 100, 40, 100, 0.9});
    near.push_back(far.back());
  }
  const long long gap = 100000000000000LL;
  for (long long f = 0; f < 10; ++f) {
    far.push_back({gap + f, 300.0 - 3 * f, 150, 40, 100, 0.9});
    near.push_back({3000 + f, 300.0 - 3 * f, 150, 40, 100, 0.9});
  }
  long long progress_calls = 0, last_done = 0;
  const auto rows_far = vtrack::apps::track_detections(
      far, 640, 480, {}, 1000000000000000LL, [&](long long done, long long) {
        ++progress_calls;
        last_done = done;
      });
  // Both run on well past the second walker's end, so both report its lost-track frames.
  const auto rows_near = vtrack::apps::track_detections(near, 640, 480, {}, 8000);
  ASSERT_EQ(rows_far.size(), rows_near.size());
  ASSERT_FALSE(rows_far.empty());
  for (std::size_t i = 0; i < rows_far.size(); ++i) {
    const long long shift = rows_near[i].frame >= 3000 ? gap - 3000 : 0;
    EXPECT_EQ(rows_far[i].frame, rows_near[i].frame + shift);
    EXPECT_EQ(rows_far[i].id, rows_near[i].id);
    EXPECT_EQ(rows_far[i].x, rows_near[i].x);
  }
  EXPECT_LT(progress_calls, 5000);  // frames stepped (at most 2000 per idle run), not counted
  EXPECT_EQ(last_done, 1000000000000000LL);
  EXPECT_THROW(vtrack::apps::track_detections(near, 640, 480, {}, 1000000000000001LL),
               vtrack::InvalidArgument);
}

TEST(HogDetector, RefusesFramesSmallerThanItsWindow) {
  vtrack::apps::HogParams p;
  p.upscale = 1.0;
  const vtrack::apps::HogPeopleDetector at_one(p);
  EXPECT_EQ(at_one.min_frame_size(), cv::Size(64, 128));
  EXPECT_NO_THROW(at_one.detect(cv::Mat(128, 64, CV_8UC3, cv::Scalar::all(90))));
  EXPECT_THROW(at_one.detect(cv::Mat(127, 64, CV_8UC3, cv::Scalar::all(90))), vtrack::InvalidArgument);
  EXPECT_THROW(at_one.detect(cv::Mat(1, 1, CV_8UC3)), vtrack::InvalidArgument);
  // Upscaled by 1.5, a 43 x 85 frame becomes 64 x 128 (cv::resize rounds).
  const vtrack::apps::HogPeopleDetector upscaled;
  EXPECT_EQ(upscaled.min_frame_size(), cv::Size(43, 85));
  EXPECT_NO_THROW(upscaled.detect(cv::Mat(85, 43, CV_8UC3, cv::Scalar::all(90))));
  try {
    upscaled.detect(cv::Mat(64, 64, CV_8UC3, cv::Scalar::all(90)));
    FAIL() << "a 64x64 frame was accepted";
  } catch (const vtrack::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("frame is 64x64"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at least 43x85"), std::string::npos) << e.what();
  }
}

}  // namespace

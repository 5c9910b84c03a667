// apps::run_background_subtraction: output kinds, and what a corrupt input leaves behind.
#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "scratch_dir.hpp"
#include "vtrack/apps/background_subtraction.hpp"
#include "vtrack/core/errors.hpp"

namespace fs = std::filesystem;
using namespace vtrack;

namespace {

class BgsAppTest : public ScratchDirTest {
 protected:
  // A 40-frame Motion-JPEG clip of a bright square moving over a grey background.
  std::string write_clip() const {
    const std::string path = (dir_ / "clip.avi").string();
    cv::VideoWriter writer(path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0, {64, 48});
    for (int i = 0; i < 40; ++i) {
      cv::Mat f(48, 64, CV_8UC3, cv::Scalar(90, 100, 110));
      f(cv::Rect(i, 10, 12, 12)).setTo(cv::Scalar(20, 200, 240));
      writer.write(f);
    }
    return path;
  }
};

}  // namespace

TEST_F(BgsAppTest, FolderGetsOnePngPerFrameAndProgressIsReported) {
  image::KdeBackgroundParams params;
  params.period = 2;
  long long last_done = 0, last_total = 0;
  const auto result = apps::run_background_subtraction(
      write_clip(), (dir_ / "y").string(), params, [&](long long done, long long total) {
        EXPECT_EQ(done, last_done + 1);
        last_done = done;
        last_total = total;
      });
  EXPECT_EQ(result.frames, 40);
  EXPECT_FALSE(result.video);
  EXPECT_EQ(last_done, 40);
  EXPECT_EQ(last_total, 40);
  const cv::Mat y = cv::imread((dir_ / "y" / "000039.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(y.type(), CV_8UC1);
  EXPECT_LT(y.at<unsigned char>(16, 44), 128);  // on the square (frame 39: columns 39..50)
  EXPECT_GT(y.at<unsigned char>(40, 5), 250);   // background
  EXPECT_FALSE(fs::exists(dir_ / "y" / "000040.png"));
}

TEST_F(BgsAppTest, TruncatedInputKeepsCompleteImagesAndNoVideo) {
  const std::string clip = write_clip();
  fs::resize_file(clip, fs::file_size(clip) / 2);
  try {
    apps::run_background_subtraction(clip, (dir_ / "y").string(), {});
    FAIL() << "truncated video accepted";
  } catch (const IoError& e) {
    const std::string what = e.what();
    const auto at = what.find("cannot decode frame ");
    ASSERT_NE(at, std::string::npos) << what;
    const int bad = std::stoi(what.substr(at + 20));
    int pngs = 0;
    for (const auto& entry : fs::directory_iterator(dir_ / "y")) {
      EXPECT_EQ(entry.path().extension(), ".png");
      EXPECT_FALSE(cv::imread(entry.path().string(), cv::IMREAD_UNCHANGED).empty()) << entry.path();
      ++pngs;
    }
    EXPECT_EQ(pngs, bad);
    EXPECT_NE(what.find("are complete"), std::string::npos) << what;
  }
  EXPECT_THROW(apps::run_background_subtraction(clip, (dir_ / "y.avi").string(), {}), IoError);
  EXPECT_FALSE(fs::exists(dir_ / "y.avi"));
  for (const auto& entry : fs::directory_iterator(dir_)) {  // nor its temporary file
    EXPECT_EQ(entry.path().filename().string().find("partial"), std::string::npos) << entry.path();
  }
}

TEST_F(BgsAppTest, BadParametersTouchNoFile) {
  image::KdeBackgroundParams params;
  params.n_samples = 0;
  EXPECT_THROW(apps::run_background_subtraction(write_clip(), (dir_ / "y").string(), params),
               InvalidArgument);
  EXPECT_FALSE(fs::exists(dir_ / "y"));
}

TEST(BgsApp, VideoExtensions) {
  EXPECT_TRUE(apps::is_video_output("a/b.avi"));
  EXPECT_TRUE(apps::is_video_output("B.MP4"));
  EXPECT_TRUE(apps::is_video_output("x.mkv"));
  EXPECT_FALSE(apps::is_video_output("frames"));
  EXPECT_FALSE(apps::is_video_output("frames.d/"));
}

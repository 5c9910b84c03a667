#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "scratch_dir.hpp"
#include "vtrack/apps/video_source.hpp"
#include "vtrack/core/errors.hpp"

namespace fs = std::filesystem;
using namespace vtrack::apps;

namespace {

class VideoSourceTest : public ScratchDirTest {
 protected:
  cv::Mat frame(int i) const {
    cv::Mat f(48, 64, CV_8UC3, cv::Scalar(i * 10 % 255, 100, 200));
    return f;
  }

  std::string write_video(int frames) const {
    const std::string path = (dir_ / "clip.avi").string();
    cv::VideoWriter writer(path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 12.0,
                           {64, 48});
    EXPECT_TRUE(writer.isOpened());
    for (int i = 0; i < frames; ++i) writer.write(frame(i));
    return path;
  }
};

}  // namespace

TEST_F(VideoSourceTest, ProbesAVideoExactly) {
  const VideoInfo info = probe_video(write_video(17));
  EXPECT_EQ(info.frame_count, 17);
  EXPECT_EQ(info.width, 64);
  EXPECT_EQ(info.height, 48);
  EXPECT_NEAR(info.fps, 12.0, 1e-6);
  EXPECT_FALSE(info.is_image_folder);
}

TEST_F(VideoSourceTest, ReadsAnImageFolderInNameOrder) {
  for (int i : {2, 0, 1}) {
    cv::imwrite((dir_ / ("f" + std::to_string(i) + ".png")).string(), frame(i));
  }
  std::ofstream(dir_ / "notes.txt") << "not an image";
  VideoSource source(dir_.string());
  EXPECT_TRUE(source.is_image_folder());
  EXPECT_EQ(source.expected_frame_count(), 3);
  cv::Mat f;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(source.read(f));
    EXPECT_EQ(f.at<cv::Vec3b>(0, 0)[0], i * 10);
  }
  EXPECT_FALSE(source.read(f));
  EXPECT_EQ(probe_video(dir_.string()).fps, 0.0);
}

TEST_F(VideoSourceTest, MissingEmptyAndNonVideoInputsAreIoErrors) {
  EXPECT_THROW(VideoSource((dir_ / "nope.avi").string()), vtrack::IoError);
  EXPECT_THROW(VideoSource(dir_.string()), vtrack::IoError);  // folder without images
  std::ofstream(dir_ / "text.avi") << "this is not a video\n";
  EXPECT_THROW(VideoSource((dir_ / "text.avi").string()), vtrack::IoError);
}

TEST_F(VideoSourceTest, CorruptImageInAFolderNamesTheFrame) {
  cv::imwrite((dir_ / "a.png").string(), frame(0));
  std::ofstream(dir_ / "b.png") << "garbage";
  VideoSource source(dir_.string());
  cv::Mat f;
  ASSERT_TRUE(source.read(f));
  try {
    source.read(f);
    FAIL() << "expected IoError";
  } catch (const vtrack::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1"), std::string::npos) << e.what();
  }
}

TEST_F(VideoSourceTest, ImagesOfDifferentSizesAreAnError) {
  cv::imwrite((dir_ / "a.png").string(), frame(0));
  cv::imwrite((dir_ / "b.png").string(), cv::Mat(10, 10, CV_8UC3, cv::Scalar(0)));
  VideoSource source(dir_.string());
  cv::Mat f;
  ASSERT_TRUE(source.read(f));
  EXPECT_THROW(source.read(f), vtrack::IoError);
}

TEST_F(VideoSourceTest, TruncatedVideoIsAnErrorNotAShortVideo) {
  const std::string path = write_video(40);
  fs::resize_file(path, fs::file_size(path) / 2);
  EXPECT_THROW(probe_video(path), vtrack::IoError);
}

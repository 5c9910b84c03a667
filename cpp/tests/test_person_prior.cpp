#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "vtrack/filters/person_prior.hpp"

using vtrack::filters::whole_person_box;

namespace {

void expect_box(const cv::Rect2d& got, double x, double y, double w, double h) {
  EXPECT_DOUBLE_EQ(got.x, x);
  EXPECT_DOUBLE_EQ(got.y, y);
  EXPECT_DOUBLE_EQ(got.width, w);
  EXPECT_DOUBLE_EQ(got.height, h);
}

}  // namespace

// A 320 x 240 image, people 20 x 50 px. A box cut by a border grows out of the image to the
// person's size, its side in view kept; anything else is returned as it is.
TEST(WholePersonBox, GrowsABoxCutByTheBorderOutOfTheImage) {
  const cv::Size image(320, 240);
  const cv::Size2d person(20.0, 50.0);
  expect_box(whole_person_box({0.0, 100.0, 8.0, 50.0}, person, image), -12.0, 100.0, 20.0, 50.0);
  expect_box(whole_person_box({310.0, 100.0, 10.0, 50.0}, person, image), 310.0, 100.0, 20.0,
             50.0);
  expect_box(whole_person_box({100.0, 0.5, 20.0, 30.0}, person, image), 100.0, -19.5, 20.0, 50.0);
  expect_box(whole_person_box({100.0, 210.0, 20.0, 30.0}, person, image), 100.0, 210.0, 20.0,
             50.0);
  // Cut by a corner: both sides grow.
  expect_box(whole_person_box({0.0, 0.0, 5.0, 10.0}, person, image), -15.0, -40.0, 20.0, 50.0);
}

TEST(WholePersonBox, LeavesBoxesInViewAndBoxesAsLargeAsAPerson) {
  const cv::Size image(320, 240);
  const cv::Size2d person(20.0, 50.0);
  // Away from every border (2 px in): a narrow person in view is not widened.
  expect_box(whole_person_box({2.0, 2.0, 8.0, 30.0}, person, image), 2.0, 2.0, 8.0, 30.0);
  // At the border but already a person's size or more: unchanged.
  expect_box(whole_person_box({0.0, 100.0, 24.0, 60.0}, person, image), 0.0, 100.0, 24.0, 60.0);
  expect_box(whole_person_box({300.0, 190.0, 20.0, 50.0}, person, image), 300.0, 190.0, 20.0,
             50.0);
}

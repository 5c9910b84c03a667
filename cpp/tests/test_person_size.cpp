#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "vtrack/core/errors.hpp"
#include "vtrack/models/person_size.hpp"

using vtrack::InvalidArgument;
using vtrack::models::ForegroundSizeEstimator;

namespace {

// A background image (y = 1) with dark rectangles (y = 0.1) of the given (x, y, w, h).
cv::Mat with_blobs(const std::vector<cv::Rect>& blobs, int width = 320, int height = 240) {
  cv::Mat y(height, width, CV_32F, cv::Scalar(1.0f));
  for (const auto& r : blobs) y(r).setTo(0.1f);
  return y;
}

}  // namespace

// Counted once each, big enough to be a person: three people of heights 40, 60 and 80 and a
// group three people high (half the area counted: area-weighting would favour it);
// specks below the area floor, fragments below a person of half the height (a 4 x 8 piece), and
// a tall component cut by the top border are not counted. The count median of 40, 60, 80, 230
// lies between 60 and 80 (the median of four, interpolated in log2 within the bins).
TEST(ForegroundSizeEstimator, CountsPeopleNotGroupsSpecksOrTheBorder) {
  ForegroundSizeEstimator est(std::numeric_limits<double>::infinity(), 1e-4, 0.25);  // floor 7.7 px
  EXPECT_EQ(est.person_height(), 0.0);
  std::vector<cv::Rect> blobs = {{10, 10, 10, 40}, {30, 10, 15, 60}, {60, 10, 20, 80},
                                 {90, 0, 10, 240},    // cut by the top border
                                 {110, 5, 12, 230}};  // a group of three
  for (int k = 0; k < 30; ++k) blobs.push_back({150 + 5 * (k % 20), 150 + 4 * (k / 20), 2, 2});
  for (int k = 0; k < 6; ++k) blobs.push_back({150 + 8 * k, 200, 4, 8});  // fragments
  est.observe(with_blobs(blobs));
  EXPECT_GE(est.person_height(), 60.0 / 1.045);
  EXPECT_LE(est.person_height(), 80.0 * 1.045);
  // Counted: 400 + 900 + 1600 + 2760 + 6 x 32; the specks are under the floor, the column is on
  // the top border.
  EXPECT_DOUBLE_EQ(est.weight(), 400.0 + 900.0 + 1600.0 + 12.0 * 230.0 + 6 * 32.0);
  EXPECT_EQ(est.frames(), 1);
  // With many single people the group is one count among many: the estimate is a person's.
  for (int k = 0; k < 5; ++k) est.observe(with_blobs({{10, 10, 20, 60}, {40, 10, 20, 60},
                                                      {70, 10, 20, 60}, {110, 5, 30, 180}}));
  EXPECT_NEAR(est.person_height(), 60.0, 60.0 * 0.045);
}

// With a half-life of 5 frames, after 40 frames of 100 px people the 50 px people seen before
// weigh 2^-8 as much: the median follows the scene.
TEST(ForegroundSizeEstimator, ForgetsWithTheHalfLife) {
  ForegroundSizeEstimator est(5.0, 0.0);
  for (int k = 0; k < 40; ++k) est.observe(with_blobs({{10, 10, 20, 50}, {60, 10, 20, 50}}));
  EXPECT_NEAR(est.person_height(), 50.0, 50.0 * 0.045);
  for (int k = 0; k < 40; ++k) est.observe(with_blobs({{10, 10, 40, 100}}));
  EXPECT_NEAR(est.person_height(), 100.0, 100.0 * 0.045);
  // Decayed total: each frame's 4000 px, a geometric sum with ratio 2^(-1/5).
  const double q = std::exp2(-1.0 / 5.0);
  EXPECT_NEAR(est.weight(), 4000.0 * (1 - std::pow(q, 40)) / (1 - q) +
                                2000.0 * std::pow(q, 40) * (1 - std::pow(q, 40)) / (1 - q),
              1e-6 * est.weight());
  est.reset();
  EXPECT_EQ(est.person_height(), 0.0);
}

TEST(ForegroundSizeEstimator, RejectsBadArguments) {
  EXPECT_THROW(ForegroundSizeEstimator(0.0), InvalidArgument);
  EXPECT_THROW(ForegroundSizeEstimator(10.0, 1.0), InvalidArgument);
  EXPECT_THROW(ForegroundSizeEstimator(10.0, 0.0, 0.0), InvalidArgument);
  ForegroundSizeEstimator est;
  EXPECT_THROW(est.observe(cv::Mat()), InvalidArgument);
  EXPECT_THROW(est.observe(cv::Mat(10, 10, CV_8U, cv::Scalar(0))), InvalidArgument);
  est.observe(cv::Mat(10, 10, CV_32F, cv::Scalar(1.0f)));  // no foreground: nothing learnt
  EXPECT_EQ(est.person_height(), 0.0);
  EXPECT_EQ(est.weight(), 0.0);
}

namespace {

// Frames of a ground plane seen in perspective: people (y = 0.1, width 0.35 h) whose height is
// h(foot) = height_at(foot), with their foot rows (last row) on a grid from first_foot to
// last_foot every 3 px, twelve people a frame side by side.
template <class HeightAt>
void observe_people(ForegroundSizeEstimator& est, HeightAt height_at, int first_foot,
                    int last_foot) {
  std::vector<cv::Rect> blobs;
  for (int foot = first_foot; foot <= last_foot; foot += 3) {
    const int h = static_cast<int>(std::lround(height_at(foot)));
    const int w = std::max(2, static_cast<int>(std::lround(0.35 * h)));
    blobs.push_back({10 + 52 * static_cast<int>(blobs.size()), foot - h + 1, w, h});
    if (blobs.size() == 12 || foot + 3 > last_foot) {
      est.observe(with_blobs(blobs, 640, 480));
      blobs.clear();
    }
  }
}

// The learnt line recovers the truth's slope of 0.25 within 5 % and its height within 6 % at the
// rows where people were seen.
template <class Truth>
void expect_line(const vtrack::models::PersonHeightLine& line, const Truth& truth) {
  ASSERT_TRUE(line.by_row);
  EXPECT_NEAR(line.slope, 0.25, 0.25 * 0.05);
  for (const double foot : {170.0, 250.0, 350.0, 460.0}) {
    EXPECT_NEAR(line.at(foot), truth(foot), 0.06 * truth(foot)) << "foot row " << foot;
  }
}

}  // namespace

// A camera without roll above a ground plane: h = 0.25 foot - 10 (30 px at row 160, 105 at row
// 460). The weighted Theil-Sen line through the row bands' count medians recovers the slope and
// intercept: each band's median is that of its people's feet spread over the band (a band is 30
// rows, its centre's height within 1/16 octave of the binned median), so the slope within 5 %
// and the height at any row where people were seen within 6 %.
TEST(ForegroundSizeEstimator, LearnsTheHeightAsALineOfTheFootRow) {
  ForegroundSizeEstimator est(std::numeric_limits<double>::infinity(), 1e-4, 0.35);
  auto truth = [](double foot) { return 0.25 * foot - 10.0; };
  observe_people(est, truth, 160, 470);
  const auto line = est.person_height_line();
  expect_line(line, truth);
  // Not extrapolated without bound: above the people's rows the line is floored at half its
  // value at the top band, so it never reaches the horizon's zero.
  EXPECT_GT(line.at(0.0), 0.4 * truth(170.0));
  EXPECT_LE(line.at(0.0), line.at(170.0));
}

// An overhead-like scene (every person 50 px tall at every row) and noise around a constant
// height give no supported slope: the line is the constant person_height(). A scene seen at one
// row band only cannot support a slope either.
TEST(ForegroundSizeEstimator, FallsBackToTheConstantWithoutPerspective) {
  ForegroundSizeEstimator flat(std::numeric_limits<double>::infinity(), 1e-4, 0.35);
  observe_people(flat, [](double) { return 50.0; }, 60, 470);
  auto line = flat.person_height_line();
  EXPECT_FALSE(line.by_row);
  EXPECT_EQ(line.slope, 0.0);
  EXPECT_NEAR(line.at(100.0), 50.0, 50.0 * 0.045);
  EXPECT_DOUBLE_EQ(line.at(100.0), flat.person_height());

  // +-8 % around 50 px, alternating with the row: a Theil-Sen slope near 0, under a tenth of
  // the height over the rows seen.
  ForegroundSizeEstimator noisy(std::numeric_limits<double>::infinity(), 1e-4, 0.35);
  observe_people(noisy, [](double foot) { return (int(foot) / 3) % 2 ? 54.0 : 46.0; }, 60, 470);
  EXPECT_FALSE(noisy.person_height_line().by_row);

  ForegroundSizeEstimator one_band(std::numeric_limits<double>::infinity(), 1e-4, 0.35);
  observe_people(one_band, [](double foot) { return 0.25 * foot - 10.0; }, 400, 428);
  EXPECT_FALSE(one_band.person_height_line().by_row);
  EXPECT_EQ(ForegroundSizeEstimator().person_height_line().intercept, 0.0);
}

// People walking in lanes (PersonHeightLine::well_supported, what the multi-Bernoulli tracker
// asks of a line): a few people, each filling one row band for many frames, are no evidence of
// perspective, whatever their heights (the counts are components x frames, not
// people). Five people in five lanes on the line h = 0.25 foot - 10 give it; three lanes (the
// heights of tests/test_track_video.py's scene 3, which fitted a spurious line) give none, nor
// five lanes whose heights rise with the row but where two people are 30 % taller than the line
// through the other three (a fit share of 0.6).
TEST(ForegroundSizeEstimator, AFewPeopleInLanesAreNoLine) {
  auto observe_lanes = [](const std::vector<std::pair<int, double>>& lanes) {
    ForegroundSizeEstimator est(std::numeric_limits<double>::infinity(), 1e-4, 0.35);
    for (int frame = 0; frame < 20; ++frame) {
      std::vector<cv::Rect> blobs;
      for (const auto& [foot, height] : lanes) {
        const int h = static_cast<int>(std::lround(height));
        const int w = static_cast<int>(std::lround(0.35 * height));
        blobs.push_back({10 + 4 * frame + 100 * static_cast<int>(blobs.size()), foot - h + 1, w, h});
      }
      est.observe(with_blobs(blobs, 640, 480));
    }
    return est.person_height_line();
  };
  auto truth = [](double foot) { return 0.25 * foot - 10.0; };
  std::vector<std::pair<int, double>> five;
  for (const int foot : {165, 225, 285, 345, 405}) five.emplace_back(foot, truth(foot));
  const auto line = observe_lanes(five);
  ASSERT_TRUE(line.well_supported());
  EXPECT_NEAR(line.slope, 0.25, 0.25 * 0.05);
  EXPECT_GT(line.fit_share, 0.99);
  EXPECT_GT(line.rising_share, 0.99);

  EXPECT_FALSE(
      observe_lanes({{47 * 2, 36 * 2}, {137 * 2, 59 * 2}, {231 * 2, 51 * 2}}).well_supported());

  five[1].second *= 1.3;
  five[3].second *= 1.3;
  const auto off = observe_lanes(five);
  EXPECT_FALSE(off.well_supported());
  EXPECT_GE(off.rising_share, vtrack::models::PersonHeightLine::kMinRisingShare);  // rising: 0.8
  EXPECT_NEAR(off.fit_share, 0.6, 0.01);
}

// PETS09's top rows at small resolutions: walls, windows and tree tops leave blobby specks, as
// wide as they are tall, big enough by area to pass the person floor (a 15 x 15 px square holds
// the area of a person a third of the median height, ~22 of ~67 px). Bands full of them would
// weigh as much as bands of people in the Theil-Sen fit and bend the line down at the top (here:
// no supported slope at all without the cut; the
// first version: slope 0.31 against the truth's 0.23 on PETS09 at 0.6x, far people predicted at
// half their height). A band whose median is under a third of the person height holds no people:
// the line is that of the people alone, and it is floored above their rows as without specks.
TEST(ForegroundSizeEstimator, SpecksAboveThePeopleDoNotBendTheLine) {
  ForegroundSizeEstimator est(std::numeric_limits<double>::infinity(), 1e-4, 0.35);
  auto truth = [](double foot) { return 0.25 * foot - 10.0; };
  observe_people(est, truth, 160, 470);
  const double h = est.person_height();
  const int side = static_cast<int>(std::ceil(std::sqrt(0.35) * h / 3.0)) + 1;
  ASSERT_LT(side, h / 3.0);  // passes the area floor, below the height cut
  // 15 specks in each of the two top bands: more than the ~10 people of any band, far fewer
  // than the 104 people in all (the person height stays theirs).
  for (int frame = 0; frame < 3; ++frame) {
    std::vector<cv::Rect> specks;
    for (int i = 0; i < 10; ++i) specks.push_back({10 + 52 * i, 5 + (i % 2) * 30, side, side});
    est.observe(with_blobs(specks, 640, 480));
  }
  EXPECT_NEAR(est.person_height(), h, 0.05 * h);
  const auto line = est.person_height_line();
  expect_line(line, truth);
  EXPECT_GT(line.at(0.0), 0.4 * truth(170.0));
}

// apps::measure_vehicles on rendered frames: vehicles abreast in adjacent lanes cut apart (the lane
// cut, with its colour step), a lone vehicle kept whole, a still blob not reported (min_travel), a
// vehicle hidden for longer than a track coasts reported once (stitch_gap); the auto blob sizes;
// which of a vehicle's two estimates answers (max_aspect, thin_views).
// The frames are drawn with OpenCV alone (road_scene.hpp), independently of vtrack's camera.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "road_scene.hpp"
#include "scratch_dir.hpp"
#include "vtrack/apps/vehicles.hpp"

namespace fs = std::filesystem;
using namespace vtrack;

namespace {

// A camera 10 m up, 9 m beside the road's near edge, looking 38 degrees across the road and 20
// degrees down, 480 x 270 pixels (focal 450 px): it sees adjacent lanes' vehicles overlapping.
models::CameraCalibration side_camera() {
  models::CameraCalibration c = road_scene::look({-9.0, 0.0, 10.0}, 38.0, 20.0);
  c.K << 450.0, 0.0, 239.5, 0.0, 450.0, 134.5, 0.0, 0.0, 1.0;
  c.image_width = 480;
  c.image_height = 270;
  return c;
}

struct PlacedVehicle {
  double x0;       // lateral position of the footprint's near side (m)
  double W, H, L;  // m
  cv::Scalar colour;
  double ahead = 0.0;  // m its front is ahead of the others' along the road
  int hidden_from = 0, hidden_to = 0;  // frames [from, to) it is not drawn (behind a wall the road's colour)
};

class VehiclePipelineTest : public ScratchDirTest {
 protected:
  // 8 frames of empty road, then the vehicles (far ones first: the nearer paint over them) driving
  // towards the camera's side of the view together, 2 m a frame, fronts level (but for `ahead`),
  // from Y = 75 m to -5 m.
  std::string write_frames(const std::vector<PlacedVehicle>& vehicles) const {
    const auto c = side_camera();
    const Eigen::Vector3d along = c.road_axis_world, lateral = along.cross(Eigen::Vector3d::UnitZ());
    const fs::path folder = dir_ / "frames";
    fs::create_directories(folder);
    for (int k = 0; k < 48; ++k) {
      cv::Mat frame(c.image_height, c.image_width, CV_8UC3, cv::Scalar(110, 110, 110));
      for (const auto& v : vehicles) {
        if (k < 8) break;
        if (k >= v.hidden_from && k < v.hidden_to) continue;
        const Eigen::Vector3d origin = v.x0 * lateral + (75.0 - 2.0 * (k - 8) - v.ahead) * along;
        frame.setTo(v.colour, road_scene::render_mask(c, road_scene::cuboid(origin, lateral, along, v.W, v.H, v.L)));
      }
      char name[32];
      std::snprintf(name, sizeof name, "%04d.png", k);
      cv::imwrite((folder / name).string(), frame);
    }
    return folder.string();
  }

  static apps::VehiclePipelineResult run(const std::string& frames, double lane_split_gap,
                                         double stitch_gap = apps::VehicleBlobParams{}.stitch_gap) {
    apps::VehiclePipelineParams params;
    params.blobs.lane_split_gap = lane_split_gap;
    params.blobs.stitch_gap = stitch_gap;
    return apps::measure_vehicles(frames, models::Camera(side_camera()), models::table1_vehicle_models(), params);
  }

  // The distinct ids of a result's track rows.
  static std::set<std::uint64_t> row_ids(const apps::VehiclePipelineResult& result) {
    std::set<std::uint64_t> ids;
    for (const auto& r : result.tracks) ids.insert(r.id);
    return ids;
  }

  // The longer of a result's two vehicles (dimensions = (W, H, L)).
  static const filters::VehicleEstimate& longer(const apps::VehiclePipelineResult& result) {
    const auto& v = result.vehicles;
    return v[0].dimensions(2) < v[1].dimensions(2) ? v[1] : v[0];
  }

  // Two vehicles, both estimated: the shorter the 1.8 x 1.5 x 4.5 m car, light, the longer heavy.
  static void expect_the_car_and_a_heavy(const apps::VehiclePipelineResult& result) {
    ASSERT_EQ(result.vehicles.size(), 2u);
    ASSERT_TRUE(result.vehicles[0].valid && result.vehicles[1].valid);
    const auto& car = &longer(result) == &result.vehicles[0] ? result.vehicles[1] : result.vehicles[0];
    EXPECT_FALSE(car.heavy);
    EXPECT_TRUE(longer(result).heavy);
    EXPECT_NEAR(car.dimensions(1), 1.5, 0.5);
    EXPECT_NEAR(car.dimensions(2), 4.5, 1.2);
  }
};

}  // namespace

TEST_F(VehiclePipelineTest, VehiclesAbreastInOneBlobAreCutIntoTheirLanes) {
  // A red car in lane 0 (X 0.85-2.65 m), nearer the camera than a green truck in lane 1 (X 4.0-6.5 m).
  const auto frames = write_frames({{4.0, 2.5, 3.6, 9.0, cv::Scalar(60, 200, 60)},
                                    {0.85, 1.8, 1.5, 4.5, cv::Scalar(60, 60, 200)}});
  const auto whole = run(frames, 0.0);
  ASSERT_EQ(whole.vehicles.size(), 1u);  // one blob all along: one vehicle
  const auto cut = run(frames, apps::VehicleBlobParams{}.lane_split_gap);
  ASSERT_NO_FATAL_FAILURE(expect_the_car_and_a_heavy(cut));
  const auto& truck = longer(cut);
  EXPECT_NEAR(truck.dimensions(1), 3.6, 0.5);
  EXPECT_GT(truck.dimensions(2), 6.5);
}

TEST_F(VehiclePipelineTest, ANearVehicleInsideAFarOnesColumnsIsCutOut) {
  // A red car in lane 0, 2.5 m ahead of a 17 m green articulated lorry in lane 1: nearer the
  // camera, the car hides the lorry's front half, which shows on both sides of it in the image
  // (checked with synthetic_road's ground truth: in every frame both are in view), so the blob's
  // lower outline is three runs, the near lane's in the middle. Without the cut one vehicle; with
  // it two, the light car and the heavy lorry.
  const auto frames = write_frames({{4.0, 2.55, 3.8, 17.0, cv::Scalar(60, 200, 60)},
                                    {0.85, 1.8, 1.5, 4.5, cv::Scalar(60, 60, 200), 2.5}});
  ASSERT_EQ(run(frames, 0.0).vehicles.size(), 1u);
  const auto cut = run(frames, apps::VehicleBlobParams{}.lane_split_gap);
  ASSERT_NO_FATAL_FAILURE(expect_the_car_and_a_heavy(cut));
  EXPECT_NEAR(longer(cut).dimensions(2), 17.0, 2.5);
}

TEST_F(VehiclePipelineTest, ALoneVehicleIsNeverCut) {
  // A bus in a near, a middle and a far lane: its lower outline stays within its width across the
  // road, so the lane cut changes nothing (the same tracks and rows as with it off), and the bus is
  // one vehicle with an estimate, heavy. (Leaving the far lane, fast across the image's right edge,
  // the bus gets a second, short track that is never fully in view, with or without the cut.)
  for (const double x0 : {0.5, 4.0, 7.5}) {
    SCOPED_TRACE(x0);
    const auto frames = write_frames({{x0, 2.55, 3.2, 12.0, cv::Scalar(200, 80, 40)}});
    const auto with_cut = run(frames, apps::VehicleBlobParams{}.lane_split_gap);
    const auto without = run(frames, 0.0);
    ASSERT_EQ(with_cut.tracks.size(), without.tracks.size());
    for (std::size_t i = 0; i < with_cut.tracks.size(); ++i) {
      EXPECT_EQ(with_cut.tracks[i].id, without.tracks[i].id);
      EXPECT_EQ(with_cut.tracks[i].x, without.tracks[i].x);
      EXPECT_EQ(with_cut.tracks[i].w, without.tracks[i].w);
    }
    int estimated = 0;
    for (const auto& e : with_cut.vehicles) {
      if (!e.valid) continue;
      ++estimated;
      EXPECT_TRUE(e.heavy);
      EXPECT_NEAR(e.dimensions(2), 12.0, 1.5);
    }
    EXPECT_EQ(estimated, 1);
    fs::remove_all(frames);
  }
}

TEST_F(VehiclePipelineTest, AVehicleHiddenLongerThanATrackCoastsIsOneVehicle) {
  // A car in lane 0 passes behind a wall the road's colour in frames 22-31: ten frames, twice the
  // frames a track coasts (lost_memory), so its track ends and a new one starts when it shows
  // again. Without stitching: two vehicles. With it: one, seen from the first of its frames to the
  // last, every row under its id, estimated light at its length from both tracks' outlines.
  const auto frames = write_frames({{0.85, 1.8, 1.5, 4.5, cv::Scalar(60, 60, 200), 0.0, 22, 32}});
  const auto apart = run(frames, apps::VehicleBlobParams{}.lane_split_gap, 0.0);
  ASSERT_EQ(apart.vehicles.size(), 2u);
  EXPECT_LT(apart.vehicles[0].last_frame, 23);
  EXPECT_GT(apart.vehicles[1].first_frame, 32);
  const auto stitched = run(frames, apps::VehicleBlobParams{}.lane_split_gap);
  ASSERT_EQ(stitched.vehicles.size(), 1u);
  const auto& car = stitched.vehicles[0];
  EXPECT_EQ(car.first_frame, apart.vehicles[0].first_frame);
  EXPECT_EQ(car.last_frame, apart.vehicles[1].last_frame);
  EXPECT_EQ(car.frames_seen, apart.vehicles[0].frames_seen + apart.vehicles[1].frames_seen);
  EXPECT_EQ(row_ids(stitched), std::set<std::uint64_t>{static_cast<std::uint64_t>(car.vehicle_id)});
  // A row for every view: apart, the first track's road line put it inside the second's first box
  // (a hidden view: no row); stitched, it is that box's own vehicle.
  EXPECT_EQ(stitched.tracks.size(), static_cast<std::size_t>(car.frames_seen));
  EXPECT_LT(apart.tracks.size(), stitched.tracks.size());
  ASSERT_TRUE(car.valid);
  EXPECT_FALSE(car.heavy);
  EXPECT_NEAR(car.dimensions(2), 4.5, 1.2);
}

TEST_F(VehiclePipelineTest, AnotherVehicleAfterAGapDoesNotContinueATrack) {
  // The car vanishes behind the wall in frame 22 for good; from frame 28 a van shows in lane 1,
  // 20 m behind where the car would be: within the gap stitching bridges, but on another road
  // line, so it stays a vehicle of its own.
  const auto frames = write_frames({{0.85, 1.8, 1.5, 4.5, cv::Scalar(60, 60, 200), 0.0, 22, 48},
                                    {4.5, 2.0, 2.2, 5.5, cv::Scalar(60, 200, 60), -20.0, 0, 28}});
  const auto result = run(frames, apps::VehicleBlobParams{}.lane_split_gap);
  ASSERT_EQ(result.vehicles.size(), 2u);
  EXPECT_LT(result.vehicles[0].last_frame, 23);
  EXPECT_GE(result.vehicles[1].first_frame, 29);
  EXPECT_EQ(row_ids(result).size(), 2u);
}

TEST(VehicleBlobSizes, FollowTheFocalLength) {
  // Auto sizes (0): the closing's side is 3 px x f / 900 rounded to an odd number (1 = off), the
  // smallest blob 150 px x (f / 900)^2; sizes given by the user are kept at any focal length.
  const apps::VehicleBlobParams automatic;
  for (const auto& [focal, closing, area] : {std::tuple{900.0, 3, 150}, std::tuple{1200.0, 5, 267},
                                             std::tuple{450.0, 3, 38}, std::tuple{300.0, 1, 17},
                                             std::tuple{1800.0, 7, 600}}) {
    SCOPED_TRACE(focal);
    const auto p = apps::blob_sizes_for(automatic, focal);
    EXPECT_EQ(p.blob_closing, closing);
    EXPECT_EQ(p.min_area, area);
  }
  apps::VehicleBlobParams given;
  given.blob_closing = 9;
  given.min_area = 40;
  const auto p = apps::blob_sizes_for(given, 300.0);
  EXPECT_EQ(p.blob_closing, 9);
  EXPECT_EQ(p.min_area, 40);
}

TEST(VehicleAnswer, OwnViewsUnlessNoOneVehiclesShape) {
  // max_aspect: the own views' answer unless it is longer than 10 times its width (two vehicles
  // in one outline, a lorry's upper half), then the joined views' if theirs is one vehicle's.
  const auto estimate = [](double W, double H, double L, int frames_used) {
    filters::VehicleEstimate e;
    e.valid = true;
    e.dimensions = Eigen::Vector3d(W, H, L);
    e.frames_used = frames_used;
    return e;
  };
  const filters::VehicleEstimate none;  // no used view
  const auto truck = estimate(2.4, 3.7, 10.5, 3), merged = estimate(0.56, 1.86, 19.8, 19);
  const auto lorry = estimate(2.55, 4.0, 16.5, 12), sliver = estimate(0.9, 1.4, 12.0, 2);
  const double aspect = apps::VehicleBlobParams{}.max_aspect;
  ASSERT_EQ(aspect, 10.0);
  const auto answer = [](const filters::VehicleEstimate& own, const filters::VehicleEstimate& joined,
                         double max_aspect) {
    apps::VehicleBlobParams params;
    params.max_aspect = max_aspect;
    params.thin_views = 0;  // below
    return apps::vehicle_answer(own, [&] { return joined; }, params);
  };
  EXPECT_EQ(answer(merged, truck, aspect).frames_used, 3);    // not one vehicle: joined
  EXPECT_EQ(answer(lorry, truck, aspect).frames_used, 12);    // 6.5 x its width: own
  EXPECT_EQ(answer(merged, sliver, aspect).frames_used, 19);  // neither: own
  EXPECT_EQ(answer(merged, none, aspect).frames_used, 19);
  EXPECT_EQ(answer(none, sliver, aspect).frames_used, 2);     // only joined: joined
  EXPECT_FALSE(answer(none, none, aspect).valid);
  EXPECT_EQ(answer(merged, truck, 0.0).frames_used, 19);      // off: own when valid
  // Exactly 10 times as long as wide is still one vehicle's shape.
  EXPECT_EQ(answer(estimate(1.0, 1.5, 10.0, 7), truck, aspect).frames_used, 7);
}

TEST(VehicleAnswer, ThinOwnViewsGiveWayToThreeTimesAsManyJoined) {
  // thin_views: an own answer from one used view (its ray fixes two of W, H, L) gives way to a
  // joined one of one vehicle's shape from 3 times as many views or more.
  const auto estimate = [](double L, int frames_used) {
    filters::VehicleEstimate e;
    e.valid = true;
    e.dimensions = Eigen::Vector3d(2.2, 3.0, L);
    e.frames_used = frames_used;
    return e;
  };
  apps::VehicleBlobParams params;
  ASSERT_EQ(params.thin_views, 1);
  int joined_calls = 0;
  const auto answer = [&](const filters::VehicleEstimate& own, const filters::VehicleEstimate& joined) {
    return apps::vehicle_answer(own, [&] { ++joined_calls; return joined; }, params).frames_used;
  };
  EXPECT_EQ(answer(estimate(7.1, 1), estimate(10.4, 9)), 9);  // 1 own view, 9 joined: joined
  EXPECT_EQ(answer(estimate(7.1, 1), estimate(10.4, 3)), 3);  // exactly 3 times as many
  EXPECT_EQ(answer(estimate(7.1, 1), estimate(10.4, 2)), 1);  // fewer than 3 times: own
  EXPECT_EQ(answer(estimate(7.1, 1), estimate(40.0, 9)), 1);  // joined not one vehicle's shape: own
  EXPECT_EQ(answer(estimate(7.1, 1), filters::VehicleEstimate{}), 1);
  EXPECT_EQ(joined_calls, 5);
  EXPECT_EQ(answer(estimate(7.1, 2), estimate(10.4, 30)), 2);  // 2 views are not thin: own, joined not refitted
  EXPECT_EQ(joined_calls, 5);
  params.thin_views = 2;
  EXPECT_EQ(answer(estimate(7.1, 2), estimate(10.4, 6)), 6);
  params.thin_views = 0;  // off
  EXPECT_EQ(answer(estimate(7.1, 1), estimate(10.4, 9)), 1);
}

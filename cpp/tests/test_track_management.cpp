// The shared track management (filters/track_management.hpp): which lost id a new track takes.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <utility>

#include "vtrack/core/errors.hpp"
#include "vtrack/filters/track_management.hpp"

using vtrack::filters::TrackManagementParams;
using vtrack::filters::TrackManager;
using vtrack::filters::TrackRecord;

namespace {

// A confirmed track `id` reported at step 0 with box `box`, moving at `velocity` per step, ends.
void lose(TrackManager& m, std::uint64_t id, const Eigen::Vector4f& box,
          const Eigen::Vector2f& velocity) {
  m.begin_step(0);
  TrackRecord r;
  r.confirmed = true;
  r.velocity = velocity;
  m.report(r, box);
  m.end(id, r);
}

// The id a new, unconfirmed track with box `box` at step `step` takes back, or 0.
std::uint64_t taken(TrackManager& m, int step, const Eigen::Vector4f& box) {
  m.begin_step(step);
  TrackRecord r;
  return m.observe(0, r, box).value_or(0);
}

TrackManagementParams params(double relabel_distance) {
  TrackManagementParams p;
  p.confirm_frames = 5;
  p.lost_memory = 30;
  p.relabel_overlap = 0.3;
  p.relabel_distance = relabel_distance;
  return p;
}

}  // namespace

// A 20 x 50 box lost at step 0 moving 3 px/step right: at step 10 it would be centred 30 px
// further, at (140, 125). A new box 1.5 widths (30 px) beyond and twice as tall does not overlap
// it: the overlap test misses it; the distance test (d = 1.5 box widths) takes it within 2 box
// sizes, not within 1.
TEST(TrackManagement, RelabelDistanceTakesANearbyNewTrackThatIoUMisses) {
  const Eigen::Vector4f lost(100, 100, 20, 50);
  const Eigen::Vector4f fresh(160, 75, 20, 100);  // centre (170, 125)
  for (const auto& [distance, expected] :
       {std::pair{0.0, std::uint64_t(0)}, {1.0, 0}, {2.0, 7}}) {
    TrackManager m(params(distance));
    lose(m, 7, lost, {3, 0});
    EXPECT_EQ(taken(m, 10, fresh), expected) << "relabel_distance " << distance;
  }
}

// Of two lost tracks within the distance, the new track takes the nearer one's id; an id is
// taken once; after lost_memory steps it is forgotten.
TEST(TrackManagement, RelabelDistanceTakesTheNearestAndForgets) {
  TrackManager m(params(3.0));
  lose(m, 4, {0, 0, 20, 50}, {0, 0});
  lose(m, 9, {40, 0, 20, 50}, {0, 0});
  // Centre (62, 25): 0.6 widths from 9's centre (50, 25) (IoU 0.25: the overlap test misses it),
  // 2.6 from 4's (10, 25).
  EXPECT_EQ(taken(m, 5, {52, 0, 20, 50}), 9u);
  EXPECT_EQ(taken(m, 5, {52, 0, 20, 50}), 4u);  // 9 is taken; 4 is within 3
  EXPECT_EQ(taken(m, 5, {52, 0, 20, 50}), 0u);
  TrackManager old(params(3.0));
  lose(old, 4, {0, 0, 20, 50}, {0, 0});
  EXPECT_EQ(taken(old, 31, {10, 0, 20, 50}), 0u);  // remembered for 30 steps only
}

TEST(TrackManagement, RejectsABadRelabelDistance) {
  for (const double bad : {-1.0, std::numeric_limits<double>::infinity()}) {
    try {
      TrackManager m(params(bad));
      ADD_FAILURE() << bad << " accepted";
    } catch (const vtrack::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("relabel_distance"), std::string::npos) << e.what();
    }
  }
}

// The shared track management (filters/track_management.hpp): which lost id a new track takes.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

namespace {

using vtrack::filters::ColourHistogram;

// Histograms of 4 bins: a red and a blue person, and a mix.
const ColourHistogram kRed{0.8f, 0.2f, 0.0f, 0.0f};
const ColourHistogram kBlue{0.0f, 0.0f, 0.3f, 0.7f};

TrackManagementParams colour_params() {
  TrackManagementParams p = params(0.0);
  p.confirm_frames = 1;
  p.appearance_rate = 0.5;
  p.appearance_sigma = 0.3;
  p.appearance_distance = 3.0;
  return p;
}

// Two confirmed tracks (ids 1 and 2) with boxes and histograms, one step of observe + resolve.
struct Pair {
  std::uint64_t id[2] = {1, 2};
  TrackRecord record[2];
  void step(TrackManager& m, int step, const Eigen::Vector4f (&box)[2],
            const ColourHistogram* (&seen)[2], const Eigen::Vector2f (&velocity)[2]) {
    m.begin_step(step);
    std::vector<TrackManager::View> views;
    for (int i = 0; i < 2; ++i) {
      record[i].velocity = velocity[i];
      m.observe(id[i], record[i], box[i], *seen[i]);
      views.push_back({&id[i], &record[i], box[i], seen[i]});
    }
    m.resolve(views);
    for (int i = 0; i < 2; ++i) m.report(record[i], box[i]);
  }
};

// Two people walk towards each other 5 px a step (red from the left, blue from the right), meet
// at step 10 (their 20 x 50 boxes overlap for steps 7-13) and walk on. `bounce`: the tracker's
// objects turn back at the meeting (object 0 ends up on blue, on the left), as the SIR's do when
// two blobs cover each other. Returns the ids of the objects on red and on blue at the end.
std::pair<std::uint64_t, std::uint64_t> cross(const TrackManagementParams& p, bool bounce,
                                              bool same_colours = false) {
  TrackManager m(p);
  Pair pair;
  for (int k = 0; k <= 20; ++k) {
    const float red_x = 5.0f * float(k), blue_x = 100.0f - 5.0f * float(k);
    const bool swapped = bounce && k > 10;
    const Eigen::Vector4f box[2] = {{swapped ? blue_x : red_x, 0, 20, 50},
                                    {swapped ? red_x : blue_x, 0, 20, 50}};
    const ColourHistogram* seen[2] = {swapped && !same_colours ? &kBlue : &kRed,
                                      swapped || same_colours ? &kRed : &kBlue};
    if (same_colours) seen[1] = &kRed;
    const Eigen::Vector2f v[2] = {{swapped ? -5.0f : 5.0f, 0}, {swapped ? 5.0f : -5.0f, 0}};
    pair.step(m, k, box, seen, v);
  }
  return bounce ? std::pair{pair.id[1], pair.id[0]} : std::pair{pair.id[0], pair.id[1]};
}

}  // namespace

// Colour: the objects that bounced at the crossing give the ids back to the people (red keeps
// 1, blue 2); without appearance the ids follow the objects; objects that did not bounce keep
// their ids.
TEST(TrackManagement, AppearanceGivesTheIdsBackAfterACrossing) {
  EXPECT_EQ(cross(colour_params(), true), std::pair(std::uint64_t(1), std::uint64_t(2)));
  EXPECT_EQ(cross(colour_params(), false), std::pair(std::uint64_t(1), std::uint64_t(2)));
  TrackManagementParams off = colour_params();
  off.appearance_rate = 0.0;
  EXPECT_EQ(cross(off, true), std::pair(std::uint64_t(2), std::uint64_t(1)));
}

// With the same colours the motion term decides: each id goes where it was heading (the red
// person's id to the object that went on to the right), whichever way the objects went.
TEST(TrackManagement, AppearanceFollowsTheMotionWhenColoursAgree) {
  EXPECT_EQ(cross(colour_params(), true, true), std::pair(std::uint64_t(1), std::uint64_t(2)));
  EXPECT_EQ(cross(colour_params(), false, true), std::pair(std::uint64_t(1), std::uint64_t(2)));
}

// A red track (id 4) and a blue one (id 9) end at step 0, 40 px apart.
TrackManager red_and_blue_lost() {
  TrackManager m(colour_params());
  m.begin_step(0);
  for (const auto& [id, box, colour] :
       {std::tuple{std::uint64_t(4), Eigen::Vector4f(0, 0, 20, 50), &kRed},
        std::tuple{std::uint64_t(9), Eigen::Vector4f(40, 0, 20, 50), &kBlue}}) {
    TrackRecord r;
    r.confirmed = true;
    std::uint64_t label = id;
    m.observe(label, r, box, *colour);
    m.resolve({{&label, &r, box, colour}});  // alone: learns its colours
    m.report(r, box);
    m.end(label, r);
  }
  return m;
}

// A new track takes, of two lost ids within appearance_distance, the one whose colours it has,
// though the other is nearer (and overlaps it); with colours beyond 2 sigma of every lost id's,
// or without a histogram, only the overlap and distance rules apply.
TEST(TrackManagement, AppearanceTakesTheLostIdOfTheSameColours) {
  const Eigen::Vector4f near_blue(45, 0, 20, 50);  // 0.25 widths from 9 (IoU 0.6), 2.25 from 4
  const Eigen::Vector4f beside_blue(62, 0, 20, 50);  // 1.1 widths from 9 (IoU 0), 3.1 from 4
  const ColourHistogram green{0.0f, 0.0f, 1.0f, 0.0f};  // rho 0.55 with blue, 0 with red
  const auto taken_by = [](const Eigen::Vector4f& box, const ColourHistogram& seen) {
    TrackManager m = red_and_blue_lost();
    m.begin_step(3);
    TrackRecord r;
    const std::uint64_t id = m.observe(0, r, box, seen).value_or(0);
    return std::pair{id, r.appearance};
  };
  EXPECT_EQ(taken_by(near_blue, kRed), std::pair(std::uint64_t(4), kRed));  // the model comes too
  EXPECT_EQ(taken_by(beside_blue, kBlue).first, 9u);
  EXPECT_EQ(taken_by(beside_blue, green).first, 0u);  // beyond 2 sigma, outside the IoU rule
  EXPECT_EQ(taken_by(near_blue, green).first, 9u);    // the IoU rule
  EXPECT_EQ(taken_by(near_blue, {}).first, 9u);
  EXPECT_EQ(taken_by(beside_blue, {}).first, 0u);
}

TEST(TrackManagement, RejectsBadAppearanceParameters) {
  for (const auto& [name, value] : {std::pair{"appearance_rate", 1.5},
                                    {"appearance_rate", -0.1},
                                    {"appearance_sigma", 0.0},
                                    {"appearance_distance", -1.0}}) {
    TrackManagementParams p = colour_params();
    p.appearance_rate = std::string(name) == "appearance_rate" ? value : p.appearance_rate;
    p.appearance_sigma = std::string(name) == "appearance_sigma" ? value : p.appearance_sigma;
    p.appearance_distance =
        std::string(name) == "appearance_distance" ? value : p.appearance_distance;
    try {
      TrackManager m(p);
      ADD_FAILURE() << name << " " << value << " accepted";
    } catch (const vtrack::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(vtrack::filters::colour_coefficient(kRed, ColourHistogram(3, 0.3f)),
               vtrack::InvalidArgument);
}

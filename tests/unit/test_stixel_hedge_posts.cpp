// Posts in a short hedge (hedge_posts.hpp): a post two strips wide inside a
// hedge group of four strips leaves the group with its own box; a tall run at
// a group's end (a car's rear beside its lower side) and a run beside a
// neighbour nearly as tall stay in their group; a post at a group's end with
// the hedge on its side away from the image centre leaves it, a car's rear or
// a pedestrian whose lower side lies toward the centre does not; the config keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <vector>

#include "hypothesis_grouping.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// One first-layer stixel per strip from u0, all at depth z, of the given visible heights.
std::vector<Stixel> strips(const StereoCamera& cam, int u0, float z, const std::vector<float>& heights_m) {
  std::vector<Stixel> st;
  for (size_t i = 0; i < heights_m.size(); ++i) {
    Stixel s;
    s.u = u0 + 5 * static_cast<int>(i);
    s.width = 5;
    s.depth_m = z;
    s.disparity = static_cast<float>(cam.disparityFromDepth(z));
    s.bottom_row = 240;
    s.top_row = s.bottom_row + 1 - static_cast<int>(heights_m[i] * cam.fy / z + 0.5f);
    st.push_back(s);
  }
  return st;
}

GroupingParams withRule(float ratio, bool at_group_end = false) {
  GroupingParams p;
  p.hedge_posts.min_ratio = ratio;
  p.hedge_posts.at_group_end = at_group_end;
  return p;
}

// The hypothesis whose box starts at column x, or nullptr.
const Hypothesis* boxAt(const std::vector<Hypothesis>& hyps, int x) {
  for (const Hypothesis& h : hyps)
    if (h.box.x == x) return &h;
  return nullptr;
}

TEST(stixelHedgePosts, APostHalfOfAShortHedgeGetsItsOwnBox) {
  // KITTI 0926 frame 9: a striped post at 20 m, 0.9 m visible, in the median
  // hedge (0.5 m) whose group is four strips: the post is the group's median.
  const StereoCamera cam = kittiLikeCamera();
  const std::vector<Stixel> st = strips(cam, 600, 20.0f, {0.55f, 0.9f, 0.9f, 0.45f});
  const std::vector<Hypothesis> off = groupStixels(st, cam, withRule(0.0f));
  ASSERT_EQ(off.size(), 1u);
  EXPECT_EQ(off[0].box.w, 20) << "without the rule the post is the hedge's box";

  const std::vector<Hypothesis> on = groupStixels(st, cam, withRule(1.3f));
  ASSERT_EQ(on.size(), 1u) << "the one-strip hedge parts are too small to be kept";
  EXPECT_EQ(on[0].box.x, 605);
  EXPECT_EQ(on[0].box.w, 10);
  EXPECT_NEAR(on[0].height_m, 0.9f, 0.05f);
}

TEST(stixelHedgePosts, TallRunsAtAnEndOrBesideATallNeighbourStayInTheirGroup) {
  const StereoCamera cam = kittiLikeCamera();
  const GroupingParams p = withRule(1.3f, true);
  // A car's rear (1.4 m) at the end of its lower receding side (the group
  // starts left of the image centre column, 609.6: not a hedge's outer end).
  const std::vector<Stixel> end = strips(cam, 600, 20.0f, {1.4f, 1.4f, 0.6f, 0.6f, 0.6f});
  EXPECT_EQ(groupStixels(end, cam, p).size(), 1u);
  // A pedestrian's head strips beside shoulders nearly as tall.
  const std::vector<Stixel> person = strips(cam, 600, 20.0f, {1.5f, 1.75f, 1.75f, 1.5f});
  EXPECT_EQ(groupStixels(person, cam, p).size(), 1u);
  // A tall part elsewhere in the group (a vehicle beside the hedge) keeps it whole.
  const std::vector<Stixel> vehicle = strips(cam, 600, 20.0f, {0.5f, 0.9f, 0.9f, 0.5f, 1.4f, 1.4f});
  std::vector<const Stixel*> g;
  for (const Stixel& s : vehicle) g.push_back(&s);
  const auto [k, e] = findHedgePost(g, cam, p.hedge_posts);
  EXPECT_EQ(k, e);
}

TEST(stixelHedgePosts, APostAtAHedgeGroupsOuterEndGetsItsOwnBox) {
  // KITTI 0926 frame 5: a striped post at 18.7 m, 0.85-0.9 m visible, at the
  // left end of a hedge group right of the image centre (hedge 0.42-0.53 m).
  const StereoCamera cam = kittiLikeCamera();
  const std::vector<Stixel> right = strips(cam, 720, 18.7f, {0.9f, 0.9f, 0.45f, 0.5f, 0.45f, 0.5f});
  EXPECT_EQ(boxAt(groupStixels(right, cam, withRule(1.3f, false)), 720)->box.w, 30)
      << "without at_group_end the post is the hedge's box";
  const std::vector<Hypothesis> on = groupStixels(right, cam, withRule(1.3f, true));
  const Hypothesis* post = boxAt(on, 720);
  ASSERT_NE(post, nullptr);
  EXPECT_EQ(post->box.w, 10);
  EXPECT_NEAR(post->height_m, 0.9f, 0.05f);
  ASSERT_NE(boxAt(on, 730), nullptr) << "the hedge keeps its own box";

  // The mirror image left of the centre: the post at the group's right end.
  const std::vector<Stixel> left = strips(cam, 450, 18.7f, {0.5f, 0.45f, 0.5f, 0.45f, 0.9f, 0.9f});
  const std::vector<Hypothesis> mirrored = groupStixels(left, cam, withRule(1.3f, true));  // kept: boxAt points into it
  const Hypothesis* mirror = boxAt(mirrored, 470);
  ASSERT_NE(mirror, nullptr);
  EXPECT_EQ(mirror->box.w, 10);
}

TEST(stixelHedgePosts, ARearOrAPersonAtAnEndWithItsLowerSideTowardTheCentreStaysWhole) {
  // Synthetic wet_road 5/7, urban 11 at 23-29 m: one tall strip (a car's or
  // van's rear edge) at a group's end, beside a lower side of the same object
  // lying toward the image centre (the receding side in view faces the optical axis).
  const StereoCamera cam = kittiLikeCamera();
  const GroupingParams p = withRule(1.3f, true);
  // Right of the centre, the car's rear (1.35 m) at the right end.
  const std::vector<Stixel> rear_right = strips(cam, 690, 25.0f, {0.6f, 0.6f, 0.6f, 1.35f});
  EXPECT_EQ(groupStixels(rear_right, cam, p).size(), 1u);
  // Left of the centre, the rear at the left end.
  const std::vector<Stixel> rear_left = strips(cam, 480, 25.0f, {1.35f, 0.6f, 0.6f, 0.6f});
  EXPECT_EQ(groupStixels(rear_left, cam, p).size(), 1u);
  // A pedestrian (1.8 m) at 24 m, left of the centre, beside a 0.45 m strip
  // of its own group toward the centre (the geometry of wet_road 7 frame 16's
  // van edge).
  const std::vector<Stixel> person = strips(cam, 530, 24.3f, {1.8f, 0.45f});
  std::vector<const Stixel*> g;
  for (const Stixel& s : person) g.push_back(&s);
  const auto [k, e] = findHedgePost(g, cam, p.hedge_posts);
  EXPECT_EQ(k, e);
}

TEST(stixelHedgePosts, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["hedge_post_min_ratio"] = 1.5;
  n["hedge_post_min_height_m"] = 0.7;
  n["hedge_post_min_step_m"] = 0.3;
  n["hedge_post_max_width_m"] = 0.5;
  n["hedge_post_max_distance_m"] = 25.0;
  n["hedge_post_at_group_end"] = false;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.hedge_post_min_ratio, 1.5f);
  EXPECT_FLOAT_EQ(p.hedge_post_min_height_m, 0.7f);
  EXPECT_FLOAT_EQ(p.hedge_post_min_step_m, 0.3f);
  EXPECT_FLOAT_EQ(p.hedge_post_max_width_m, 0.5f);
  EXPECT_FLOAT_EQ(p.hedge_post_max_distance_m, 25.0f);
  EXPECT_FALSE(p.hedge_post_at_group_end);
  for (const char* key : {"hedge_post_min_ratio", "hedge_post_min_height_m", "hedge_post_min_step_m",
                          "hedge_post_max_width_m", "hedge_post_max_distance_m"})
    expectRejected(key, -1.0);
  expectRejected("hedge_post_at_group_end", -1.0);  // not true or false
  EXPECT_EQ(Params{}.hedge_post_min_ratio, 1.3f) << "on by default";
  EXPECT_TRUE(Params{}.hedge_post_at_group_end) << "on by default";
}

}  // namespace
}  // namespace nerv::stixel

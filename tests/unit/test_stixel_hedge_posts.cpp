// Posts in a short hedge (hedge_posts.hpp): a post two strips wide inside a
// hedge group of four strips leaves the group with its own box; a tall run at
// a group's end (a car's rear beside its lower side) and a run beside a
// neighbour nearly as tall stay in their group; the config keys.
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

GroupingParams withRule(float ratio) {
  GroupingParams p;
  p.hedge_posts.min_ratio = ratio;
  return p;
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
  const GroupingParams p = withRule(1.3f);
  // A car's rear (1.4 m) at the end of its lower receding side.
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

TEST(stixelHedgePosts, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["hedge_post_min_ratio"] = 1.5;
  n["hedge_post_min_height_m"] = 0.7;
  n["hedge_post_min_step_m"] = 0.3;
  n["hedge_post_max_width_m"] = 0.5;
  n["hedge_post_max_distance_m"] = 25.0;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.hedge_post_min_ratio, 1.5f);
  EXPECT_FLOAT_EQ(p.hedge_post_min_height_m, 0.7f);
  EXPECT_FLOAT_EQ(p.hedge_post_min_step_m, 0.3f);
  EXPECT_FLOAT_EQ(p.hedge_post_max_width_m, 0.5f);
  EXPECT_FLOAT_EQ(p.hedge_post_max_distance_m, 25.0f);
  for (const char* key : {"hedge_post_min_ratio", "hedge_post_min_height_m", "hedge_post_min_step_m",
                          "hedge_post_max_width_m", "hedge_post_max_distance_m"})
    expectRejected(key, -1.0);
  EXPECT_EQ(Params{}.hedge_post_min_ratio, 1.3f) << "on by default";
}

}  // namespace
}  // namespace nerv::stixel

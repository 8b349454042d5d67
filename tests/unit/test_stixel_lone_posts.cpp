// Lone posts in front of a far surface (lone_posts.hpp): a thin sign post at
// 15 m, one strip wide, in front of a facade at 30 m is kept as a hypothesis
// alone; the same post with a surface only 1.6 m behind it on one side (a trunk
// in a receding row of trees), or with open road on one side, is not; below
// lone_post_min_height_m it is not; the config keys.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "lone_posts.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_scene_queries.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// A facade at 30 m from x = -14 to -1 m, and at 15 m a post 0.06 m wide (3 px),
// placed inside one 5 px strip, 3.5 m tall.
class stixelLonePosts : public ::testing::Test {
 protected:
  static constexpr float kPostZ = 15.0f, kWallZ = 30.0f;
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  double post_x = 0;  // the post's left edge [m]

  void SetUp() override {
    paintFace(disp, scene, cam, kWallZ, -14.0, -1.0, 0.0, 8.0);
    // Left edge at column 5k + 1 near x = -4 m, so the post's 3 columns are in one strip.
    const double u = 5.0 * std::floor((cam.cx - 4.0 * cam.fx / kPostZ) / 5.0) + 1.2;
    post_x = (u - cam.cx) * kPostZ / cam.fx;
  }

  // Lateral position [m] of column u at depth z.
  double xAt(double u, float z) const { return (u - cam.cx) * z / cam.fx; }

  int topRow(double height_m) const {
    return static_cast<int>(std::lround(footRow(scene, cam, kPostZ) - height_m * cam.fy / kPostZ));
  }

  FaceColumns paintPost(double height_m) {
    return paintFace(disp, scene, cam, kPostZ, post_x, post_x + 0.06, 0.0, height_m);
  }

  int postStixels(const StixelResult& r, const FaceColumns& post) const {
    int n = 0;
    for (const Stixel& s : r.stixels)
      if (s.u < post.u1 && s.u + s.width > post.u0 && std::abs(s.depth_m - kPostZ) < 1.0f) ++n;
    return n;
  }
};

TEST_F(stixelLonePosts, AThinPostInFrontOfAFarFacadeIsKeptAlone) {
  const FaceColumns post = paintPost(3.5);
  Params rule_off;
  rule_off.lone_post_min_height_m = 0.0f;
  const StixelResult off = estimateStixels(disp, cam, rule_off);
  ASSERT_EQ(postStixels(off, post), 1) << "the post is one first-layer strip";
  EXPECT_FALSE(hypothesisAt(off.hypotheses, kPostZ, post.u0, post.u1)) << "a one-stixel group is dropped";

  const StixelResult on = estimateStixels(disp, cam, Params{});
  const std::optional<Hypothesis> h = hypothesisAt(on.hypotheses, kPostZ, post.u0, post.u1);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->num_stixels, 1);
  EXPECT_NEAR(h->box.y, topRow(3.5), 3) << "top: the post's top";
  EXPECT_NEAR(h->box.y + h->box.h - 1, footRow(scene, cam, kPostZ), 3) << "bottom: its foot";
  EXPECT_LE(h->box.x, post.u0);
  EXPECT_GE(h->box.x + h->box.w, post.u1);
  EXPECT_LE(h->box.w, 6) << "one strip wide, not the facade";
  EXPECT_NEAR(h->z_m, kPostZ, 0.5);
  // Nothing else changed: the facade's hypotheses are the same with and without.
  EXPECT_EQ(on.hypotheses.size(), off.hypotheses.size() + 1);
}

TEST_F(stixelLonePosts, ASurfaceJustBehindItOnOneSideKeepsItOut) {
  // A trunk in a row of trees: on its right a face 1.6 m behind it (beyond the
  // grouping gap, 2.5 px below its disparity).
  const FaceColumns post = paintPost(3.5);
  const FaceColumns near = paintFace(disp, scene, cam, kPostZ + 1.6f, xAt(post.u1 + 1, kPostZ + 1.6f),
                                     xAt(post.u1 + 60, kPostZ + 1.6f), 0.0, 3.0);
  ASSERT_GT(near.u0, post.u1 - 1);
  const StixelResult on = estimateStixels(disp, cam, Params{});
  ASSERT_EQ(postStixels(on, post), 1);
  EXPECT_FALSE(hypothesisAt(on.hypotheses, kPostZ, post.u0, post.u1));
  EXPECT_TRUE(hypothesisAt(on.hypotheses, kPostZ + 1.6f, near.u0, near.u1).has_value()) << "the face keeps its box";
  Params no_gap;
  no_gap.lone_post_min_gap_m = 0.0f;
  no_gap.lone_post_min_step_px = 0.0f;
  EXPECT_TRUE(hypothesisAt(estimateStixels(disp, cam, no_gap).hypotheses, kPostZ, post.u0, post.u1).has_value())
      << "kept without the gap: the face is its right neighbour";
}

TEST_F(stixelLonePosts, OpenRoadOnOneSideKeepsItOut) {
  // The post right of the facade's end: free road on its right.
  disp = renderDisparity(scene, cam);
  const FaceColumns post = paintPost(3.5);
  paintFace(disp, scene, cam, kWallZ, -14.0, xAt(post.u0 - 1, kWallZ), 0.0, 8.0);
  const StixelResult on = estimateStixels(disp, cam, Params{});
  ASSERT_EQ(postStixels(on, post), 1);
  EXPECT_FALSE(hypothesisAt(on.hypotheses, kPostZ, post.u0, post.u1));
}

TEST_F(stixelLonePosts, AShortPostIsNoLonePost) {
  // 1.2 m, below lone_post_min_height_m (2.5): a bollard, a stray strip.
  const FaceColumns post = paintPost(1.2);
  const StixelResult on = estimateStixels(disp, cam, Params{});
  ASSERT_EQ(postStixels(on, post), 1);
  EXPECT_FALSE(hypothesisAt(on.hypotheses, kPostZ, post.u0, post.u1));
  Params low;
  low.lone_post_min_height_m = 1.0f;
  EXPECT_TRUE(hypothesisAt(estimateStixels(disp, cam, low).hypotheses, kPostZ, post.u0, post.u1).has_value());
}

TEST(stixelLonePostsKeys, AreReadAndRangeChecked) {
  expectFloatKeysRead({{"lone_post_min_height_m", &Params::lone_post_min_height_m},
                       {"lone_post_max_distance_m", &Params::lone_post_max_distance_m},
                       {"lone_post_min_gap_m", &Params::lone_post_min_gap_m},
                       {"lone_post_min_step_px", &Params::lone_post_min_step_px}},
                      {2.0, 30.0, 4.0, 2.5});
  expectRejected("lone_post_min_height_m", 25.0);
  expectRejected("lone_post_side_strips", 0);
  expectRejected("lone_post_side_strips", 21);
  EXPECT_EQ(Params{}.lone_post_min_height_m, 2.5f) << "on by default";
}

TEST(stixelLonePostsKeys, FindsOnlyPostsWithFarNeighboursOnBothSides) {
  // findLonePosts on constructed stixels: strips of 5 px, the post at u 100.
  const StereoCamera cam = kittiLikeCamera();
  auto stixel = [&](int u, float z, int top, int bottom) {
    Stixel s;
    s.u = u, s.width = 5, s.top_row = top, s.bottom_row = bottom, s.depth_m = z;
    s.disparity = static_cast<float>(cam.disparityFromDepth(z));
    return s;
  };
  const Stixel post = stixel(100, 15.0f, 70, 245);  // 3.7 m
  LonePostParams p;
  p.min_height_m = 2.5f;
  EXPECT_EQ(findLonePosts({stixel(90, 29.0f, 140, 205), post, stixel(110, 24.0f, 106, 215)}, cam, p).size(), 1u);
  EXPECT_TRUE(findLonePosts({stixel(95, 16.0f, 140, 205), post, stixel(110, 29.0f, 106, 215)}, cam, p).empty())
      << "a neighbour 1 m behind";
  EXPECT_TRUE(findLonePosts({stixel(95, 12.0f, 140, 205), post, stixel(110, 29.0f, 106, 215)}, cam, p).empty())
      << "a nearer neighbour";
  EXPECT_TRUE(findLonePosts({post, stixel(110, 29.0f, 106, 215)}, cam, p).empty()) << "nothing on the left";
  EXPECT_EQ(findLonePosts({stixel(85, 16.0f, 140, 205), stixel(95, 29.0f, 140, 205), post, stixel(110, 29.0f, 106, 215)},
                          cam, p).size(), 1u)
      << "a neighbour beyond side_strips (2) does not count";
  p.min_height_m = 0.0f;
  EXPECT_TRUE(findLonePosts({stixel(90, 29.0f, 140, 205), post, stixel(110, 24.0f, 106, 215)}, cam, p).empty())
      << "0 = off";
}

}  // namespace
}  // namespace nerv::stixel

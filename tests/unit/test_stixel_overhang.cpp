// Overhangs end the objects below them (overhang_cut.hpp): a pedestrian under
// a tree crown on rendered disparity, and a sign plate that must stay in its
// post's box; the config keys of the rule.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// The hypothesis at depth z whose box holds column u (nullptr if none).
const Hypothesis* at(const std::vector<Hypothesis>& hs, float z, int u) {
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < 1.0f && h.box.x <= u && u < h.box.x + h.box.w) return &h;
  return nullptr;
}

TEST(stixelOverhang, APedestrianUnderATreeCrownGetsAPedestriansBox) {
  // A 1.75 m pedestrian (0.6 m wide) at 10 m under a crown at the same depth,
  // 3 m wide, 2.0-4.5 m over the road; nothing valid between head and crown.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  paintFace(disp, scene, cam, 10.0f, -0.3, 0.3, 0.0, 1.75);
  paintFace(disp, scene, cam, 10.0f, -1.5, 1.5, 2.0, 4.5);
  const int u = static_cast<int>(cam.cx);
  Params off;
  off.overhang_min_reach_m = 0.0f;
  const StixelResult without = estimateStixels(disp, cam, off);  // kept: `at` points into it
  const Hypothesis* tree = at(without.hypotheses, 10.0f, u);
  ASSERT_NE(tree, nullptr);
  EXPECT_GT(tree->height_m, 4.0f) << "without the rule the pedestrian's strips run up through the crown";

  const StixelResult with = estimateStixels(disp, cam, Params{});
  const Hypothesis* ped = at(with.hypotheses, 10.0f, u);
  ASSERT_NE(ped, nullptr);
  EXPECT_NEAR(ped->height_m, 1.75f, 0.15f);
  EXPECT_NEAR(ped->width_m, 0.6f, 0.15f);
}

TEST(stixelOverhang, ASignPlateStaysInItsPostsBoxAndAWallBesideIsNoOverhang) {
  const StereoCamera cam = kittiLikeCamera();
  const int u = static_cast<int>(cam.cx);
  {
    // A 3 m sign pole (0.12 m, drawn 0.5 m wide so that it is wider than the
    // rule's minimum) with a 0.6 m plate at 2.4-3.0 m: the plate reaches
    // 0.05 m beside the post, far less than an overhang.
    RoadScene scene;
    cv::Mat disp = renderDisparity(scene, cam);
    paintFace(disp, scene, cam, 12.0f, -0.25, 0.25, 0.0, 3.0);
    paintFace(disp, scene, cam, 12.0f, -0.3, 0.3, 2.4, 3.0);
    const StixelResult result = estimateStixels(disp, cam, Params{});  // kept: `at` points into it
    const Hypothesis* pole = at(result.hypotheses, 12.0f, u);
    ASSERT_NE(pole, nullptr);
    EXPECT_NEAR(pole->height_m, 3.0f, 0.2f);
  }
  {
    // A 0.6 m wide thing at 10 m, filled 0-1.8 m and 2.0-3.0 m, with a face at
    // its depth 0.2 m beside it (another group: lateral gap 0.1 m here) over
    // 2.0-3.0 m: an overhang, the thing is cut to 1.8 m. When that face
    // stands on the road (a wall, 0-3 m) it is beside the thing on every row
    // and no overhang: the thing keeps its 3 m.
    Params p;
    p.group_lateral_gap_m = 0.1f;
    for (const double wall_bottom_m : {2.0, 0.0}) {
      RoadScene scene;
      cv::Mat disp = renderDisparity(scene, cam);
      paintFace(disp, scene, cam, 10.0f, -0.3, 0.3, 0.0, 1.8);
      paintFace(disp, scene, cam, 10.0f, -0.3, 0.3, 2.0, 3.0);
      paintFace(disp, scene, cam, 10.0f, 0.5, 3.0, wall_bottom_m, 3.0);
      const StixelResult result = estimateStixels(disp, cam, p);  // kept: `at` points into it
      const Hypothesis* h = at(result.hypotheses, 10.0f, u);
      ASSERT_NE(h, nullptr);
      EXPECT_NEAR(h->height_m, wall_bottom_m > 0 ? 1.8f : 3.0f, 0.15f) << "face from " << wall_bottom_m << " m";
    }
  }
}

TEST(stixelOverhang, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["overhang_min_reach_m"] = 1.0;
  n["overhang_min_fill"] = 0.5;
  n["overhang_min_height_m"] = 1.2;
  n["overhang_min_width_m"] = 0.4;
  n["overhang_max_width_m"] = 1.5;
  n["overhang_max_distance_m"] = 30.0;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.overhang_min_reach_m, 1.0f);
  EXPECT_FLOAT_EQ(p.overhang_min_fill, 0.5f);
  EXPECT_FLOAT_EQ(p.overhang_min_height_m, 1.2f);
  EXPECT_FLOAT_EQ(p.overhang_min_width_m, 0.4f);
  EXPECT_FLOAT_EQ(p.overhang_max_width_m, 1.5f);
  EXPECT_FLOAT_EQ(p.overhang_max_distance_m, 30.0f);
  for (const char* key : {"overhang_min_reach_m", "overhang_min_fill", "overhang_min_height_m",
                          "overhang_min_width_m", "overhang_max_width_m", "overhang_max_distance_m"}) {
    expectRejected(key, -1.0);
  }
}

}  // namespace
}  // namespace nerv::stixel

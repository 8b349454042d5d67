// Two pedestrians side by side (person_pairs.hpp): on rendered disparity a
// pair one behind the other by 0.8 m gets two boxes, a car's flat rear of the
// same width stays one; with a blended strip between the two the pair is cut
// and the strip dropped, but not when the parts are two strips each (far);
// the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "person_pairs.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

int countNear(const std::vector<Hypothesis>& hs, float z0, float z1) {
  int n = 0;
  for (const Hypothesis& h : hs) n += h.z_m > z0 && h.z_m < z1 ? 1 : 0;
  return n;
}

TEST(stixelPersonPairs, TwoPedestriansSideBySideGetTwoBoxes) {
  // 0.6 m wide, 1.75 m tall, at 14.2 m and 15.0 m (1.5 px apart), touching.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const FaceColumns left = paintFace(disp, scene, cam, 15.0f, -0.6, 0.0, 0.0, 1.75);
  const FaceColumns right = paintFace(disp, scene, cam, 14.2f, 0.0, 0.6, 0.0, 1.75);
  Params off;
  off.person_pair_min_step_px = 0.0f;
  EXPECT_EQ(countNear(estimateStixels(disp, cam, off).hypotheses, 13.5f, 15.7f), 1) << "off: one box";
  const auto hs = estimateStixels(disp, cam, Params{}).hypotheses;
  ASSERT_EQ(countNear(hs, 13.5f, 15.7f), 2);
  for (const Hypothesis& h : hs) {
    if (h.z_m < 13.5f || h.z_m > 15.7f) continue;
    const FaceColumns& f = h.z_m > 14.6f ? left : right;
    EXPECT_NEAR(h.box.x, f.u0, 5) << "z " << h.z_m;
    EXPECT_NEAR(h.box.x + h.box.w, f.u1, 5) << "z " << h.z_m;
    EXPECT_NEAR(h.height_m, 1.75f, 0.15f);
  }
}

TEST(stixelPersonPairs, ACarsFlatRearStaysWhole) {
  // 1.7 m wide, 1.45 m tall at 15 m: two person-sized halves, but no step.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  paintFace(disp, scene, cam, 15.0f, -0.85, 0.85, 0.0, 1.45);
  EXPECT_EQ(countNear(estimateStixels(disp, cam, Params{}).hypotheses, 14.0f, 16.0f), 1);
}

TEST(stixelPersonPairs, ABlendedStripBetweenThePairIsDropped) {
  // Urban seed 12 frame 5: 24.6-25.0 px | 25.5 | 26.1-26.4 at 15 m, heads lost
  // (tops 1.55 m); the pair, the blend and a far pair of two strips a side.
  const StereoCamera cam = kittiLikeCamera();
  const GroundModel g = levelRoad(cam);
  PersonPairParams p;
  p.min_step_px = 0.8f;
  p.max_blend_strips = 1;
  auto pair = [&](double z_left, double z_blend, double z_right, int strips) {
    std::vector<Stixel> own;
    int u = 900;
    for (int k = 0; k < strips; ++k, u += 5) own.push_back(stixelOnRoad(cam, u, z_left, 1.55));
    own.push_back(stixelOnRoad(cam, u, z_blend, 1.55)), u += 5;
    for (int k = 0; k < strips; ++k, u += 5) own.push_back(stixelOnRoad(cam, u, z_right, 1.55));
    return own;
  };
  auto cutOf = [&](const std::vector<Stixel>& own, const PersonPairParams& q) {
    std::vector<const Stixel*> group;
    for (const Stixel& s : own) group.push_back(&s);
    return findPersonPair(group, cam, &g, q);
  };
  const std::vector<Stixel> near = pair(15.75, 15.25, 14.8, 5);
  const GapCut c = cutOf(near, p);
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.lo, 925) << "the left part keeps its five strips";
  EXPECT_EQ(c.hi, 930) << "the blended strip belongs to neither";
  PersonPairParams none = p;
  none.max_blend_strips = 0;
  EXPECT_FALSE(cutOf(near, none).found) << "without the blend the parts are not flat";
  // At 32 m a person is two strips: a blend there reads like a car's receding side.
  EXPECT_FALSE(cutOf(pair(33.0, 31.2, 29.5, 2), p).found);
  PersonPairParams two = p;
  two.min_blend_part_strips = 2;
  EXPECT_TRUE(cutOf(pair(33.0, 31.2, 29.5, 2), two).found) << "control: the far pair is cut with two strips a side";
}

TEST(stixelPersonPairs, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["person_pair_min_step_px"] = 1.0;
  n["person_pair_min_step_m"] = 0.4;
  n["person_pair_min_width_m"] = 0.25;
  n["person_pair_max_width_m"] = 0.9;
  n["person_pair_min_height_m"] = 1.3;
  n["person_pair_max_height_m"] = 2.1;
  n["person_pair_max_spread_px"] = 0.6;
  n["person_pair_max_blend_strips"] = 2;
  n["person_pair_min_blend_part_strips"] = 4;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.person_pair_min_step_px, 1.0f);
  EXPECT_FLOAT_EQ(p.person_pair_min_step_m, 0.4f);
  EXPECT_FLOAT_EQ(p.person_pair_min_width_m, 0.25f);
  EXPECT_FLOAT_EQ(p.person_pair_max_width_m, 0.9f);
  EXPECT_FLOAT_EQ(p.person_pair_min_height_m, 1.3f);
  EXPECT_FLOAT_EQ(p.person_pair_max_height_m, 2.1f);
  EXPECT_FLOAT_EQ(p.person_pair_max_spread_px, 0.6f);
  EXPECT_EQ(p.person_pair_max_blend_strips, 2);
  EXPECT_EQ(p.person_pair_min_blend_part_strips, 4);
  for (const char* key : {"person_pair_min_step_px", "person_pair_min_step_m", "person_pair_min_width_m",
                          "person_pair_max_width_m", "person_pair_min_height_m", "person_pair_max_height_m",
                          "person_pair_max_spread_px", "person_pair_max_blend_strips", "person_pair_min_blend_part_strips"})
    expectRejected(key, -1.0);
  expectRejected("person_pair_max_blend_strips", 4);
}

}  // namespace
}  // namespace nerv::stixel

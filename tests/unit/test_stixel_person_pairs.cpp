// Two pedestrians side by side (person_pairs.hpp): on rendered disparity a
// pair one behind the other by 0.8 m gets two boxes, a car's flat rear of the
// same width stays one; the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
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

TEST(stixelPersonPairs, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["person_pair_min_step_px"] = 1.0;
  n["person_pair_min_step_m"] = 0.4;
  n["person_pair_min_width_m"] = 0.25;
  n["person_pair_max_width_m"] = 0.9;
  n["person_pair_min_height_m"] = 1.3;
  n["person_pair_max_height_m"] = 2.1;
  n["person_pair_max_spread_px"] = 0.6;
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
  for (const char* key : {"person_pair_min_step_px", "person_pair_min_step_m", "person_pair_min_width_m",
                          "person_pair_max_width_m", "person_pair_min_height_m", "person_pair_max_height_m",
                          "person_pair_max_spread_px"})
    expectRejected(key, -1.0);
}

}  // namespace
}  // namespace nerv::stixel

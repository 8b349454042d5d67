// Road users beside a vehicle at about its depth (height_steps.hpp): a cyclist
// beside a lower parked car, or nearer than it, on rendered disparity leaves the
// car's box; a car alone, a van's tall body, a van's receding side and a
// pedestrian beside a taller wall stay whole; the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "hypothesis_grouping.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// The hypotheses within 1.5 m of depth z whose box holds column u.
std::vector<Hypothesis> at(const std::vector<Hypothesis>& hs, float z, int u) {
  std::vector<Hypothesis> out;
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < 1.5f && h.box.x <= u && u < h.box.x + h.box.w) out.push_back(h);
  return out;
}

// A cyclist seen from behind (0.6 m wide) at z_bike, a parked car (1.8 m
// wide) right beside it at z_car: one box with `off`, two with the defaults.
void expectCyclistLeavesTheCar(float z_bike, float bike_top_m, float z_car, float car_top_m, const Params& off) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const FaceColumns bike = paintFace(disp, scene, cam, z_bike, -0.3, 0.3, 0.0, bike_top_m);
  paintFace(disp, scene, cam, z_car, 0.3, 2.1, 0.0, car_top_m);
  const int u = static_cast<int>(cam.cx);
  const auto merged = at(estimateStixels(disp, cam, off).hypotheses, 0.5f * (z_bike + z_car), u);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_GT(merged[0].width_m, 1.8f) << "without the rule cyclist and car share one box";

  const auto hs = estimateStixels(disp, cam, Params{}).hypotheses;
  const auto cyclist = at(hs, z_bike, u);
  ASSERT_EQ(cyclist.size(), 1u);
  EXPECT_NEAR(cyclist[0].box.x, bike.u0, 3);
  EXPECT_NEAR(cyclist[0].box.x + cyclist[0].box.w, bike.u1, 5);  // strip-quantised at the cut
  EXPECT_NEAR(cyclist[0].height_m, bike_top_m, 0.15f);
  const auto car = at(hs, z_car, bike.u1 + 20);
  ASSERT_EQ(car.size(), 1u);
  EXPECT_NEAR(car[0].height_m, car_top_m, 0.15f);
  EXPECT_GE(car[0].box.x, cyclist[0].box.x + cyclist[0].box.w) << "the car's box stays off the cyclist";
}

TEST(stixelHeightSteps, ACyclistBesideAParkedCarGetsItsOwnBox) {
  // 1.8 m over a 1.45 m car 1 m behind it at 25 m (0.6 px: no depth step).
  Params off;
  off.height_step_min_m = 0.0f;
  off.depth_step_min_m = 0.0f;
  expectCyclistLeavesTheCar(25.0f, 1.8f, 26.0f, 1.45f, off);
}

TEST(stixelHeightSteps, ACarAVanAndAPedestrianBesideAWallStayWhole) {
  const StereoCamera cam = kittiLikeCamera();
  const int u = static_cast<int>(cam.cx);
  // A car alone, a van (2 m wide body, 1.9 m tall, behind a 1.0 m bonnet
  // 0.8 m long: the tall end is wider than a road user), a pedestrian
  // (0.6 m, 1.75 m) beside a 2.5 m wall at its depth (the end is lower).
  struct Face { double x0, x1, top; };
  const std::vector<std::vector<Face>> scenes = {
      {{-0.9, 0.9, 1.45}},
      {{-1.0, 1.0, 1.9}, {1.0, 1.8, 1.0}},
      {{-0.3, 0.3, 1.75}, {0.3, 3.0, 2.5}},
  };
  for (size_t k = 0; k < scenes.size(); ++k) {
    RoadScene scene;
    cv::Mat disp = renderDisparity(scene, cam);
    for (const Face& f : scenes[k]) paintFace(disp, scene, cam, 20.0f, f.x0, f.x1, 0.0, f.top);
    EXPECT_EQ(at(estimateStixels(disp, cam, Params{}).hypotheses, 20.0f, u).size(), 1u) << "scene " << k;
    std::vector<Hypothesis> hs = estimateStixels(disp, cam, Params{}).hypotheses;
    int near = 0;
    for (const Hypothesis& h : hs) near += std::abs(h.z_m - 20.0f) < 1.5f ? 1 : 0;
    EXPECT_EQ(near, 1) << "scene " << k << " was cut";
  }
}

TEST(stixelHeightSteps, GroupingCutsOnlyAPersonSizedTallEnd) {
  // Stixels at 30 m: a 5-strip car (1.4 m, 1 m wide) with a 2-strip end of
  // 1.8 m on either side, or a 2-strip end of 2.6 m (a post or a tree: no
  // road user); a 3-strip rest (0.6 m: a pedestrian's shoulder) stays.
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  p.height_steps.min_step_m = 0.25f;
  auto make = [&](int u, float height_m) {
    Stixel s;
    s.u = u, s.width = 5, s.depth_m = 30.0f;
    s.disparity = static_cast<float>(cam.disparityFromDepth(30.0));
    s.bottom_row = 250;
    s.top_row = s.bottom_row - static_cast<int>(height_m * cam.fy / 30.0f);
    return s;
  };
  for (const bool left : {true, false}) {
    std::vector<Stixel> st;
    for (int k = 0; k < 7; ++k) st.push_back(make(600 + 5 * k, (left ? k < 2 : k >= 5) ? 1.8f : 1.4f));
    const auto hs = groupStixels(st, cam, p);
    ASSERT_EQ(hs.size(), 2u) << (left ? "left" : "right");
    EXPECT_EQ(hs[left ? 0 : 1].num_stixels, 2);
    EXPECT_EQ(hs[left ? 1 : 0].box.x, left ? 610 : 600);
  }
  std::vector<Stixel> st;
  for (int k = 0; k < 7; ++k) st.push_back(make(600 + 5 * k, k < 2 ? 2.6f : 1.4f));
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u);
  std::vector<Stixel> shoulder(st.begin(), st.begin() + 5);
  for (Stixel& s : shoulder) s.top_row = s.bottom_row - static_cast<int>((s.u < 610 ? 1.8f : 1.4f) * cam.fy / 30.0f);
  EXPECT_EQ(groupStixels(shoulder, cam, p).size(), 1u) << "the rest is no vehicle";
  p.height_steps.min_step_m = 0.0f;
  for (Stixel& s : st) s.top_row = s.bottom_row - static_cast<int>((s.u < 610 ? 1.8f : 1.4f) * cam.fy / 30.0f);
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u) << "off";
}

TEST(stixelHeightSteps, ACyclistNearerThanTheCarBesideItGetsItsOwnBox) {
  // 1.6 m (little above the 1.5 m car: no height step) at 20 m, the car 1.3 m
  // farther (1.2 px): joined by the 1.5 m grouping gap, cut by the depth step.
  Params off;
  off.depth_step_min_m = 0.0f;
  expectCyclistLeavesTheCar(20.0f, 1.6f, 21.3f, 1.5f, off);
}

TEST(stixelHeightSteps, AVansRecedingSideIsNoRoadUser) {
  // A van's rear (2 m tall, 5 strips at 20 m) with its side receding behind
  // it on the right (2 strips, 1.5 m and 3 m farther): a narrow, person-tall
  // end with a depth step, but farther than its neighbours, so it stays.
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  p.height_steps.min_step_m = 0.25f;
  p.height_steps.min_depth_step_m = 1.0f;
  p.side_max_stixels = 0;
  std::vector<Stixel> st;
  for (int k = 0; k < 7; ++k) {
    const float z = k < 5 ? 20.0f : k == 5 ? 21.4f : 21.8f;
    Stixel s;
    s.u = 600 + 5 * k, s.width = 5, s.depth_m = z;
    s.disparity = static_cast<float>(cam.disparityFromDepth(z));
    s.bottom_row = 250;
    s.top_row = s.bottom_row - static_cast<int>(1.9f * cam.fy / z);
    st.push_back(s);
  }
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u);
}

TEST(stixelHeightSteps, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["height_step_min_m"] = 0.3;
  n["height_step_max_width_m"] = 0.9;
  n["height_step_min_height_m"] = 1.4;
  n["height_step_max_height_m"] = 2.1;
  n["height_step_min_rest_stixels"] = 3;
  n["height_step_min_rest_width_m"] = 0.8;
  n["height_step_max_distance_m"] = 35.0;
  n["depth_step_min_m"] = 1.2;
  n["depth_step_min_px"] = 0.7;
  n["depth_step_max_spread_px"] = 0.4;
  n["depth_step_min_height_m"] = 1.4;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.height_step_min_m, 0.3f);
  EXPECT_FLOAT_EQ(p.height_step_max_width_m, 0.9f);
  EXPECT_FLOAT_EQ(p.height_step_min_height_m, 1.4f);
  EXPECT_FLOAT_EQ(p.height_step_max_height_m, 2.1f);
  EXPECT_EQ(p.height_step_min_rest_stixels, 3);
  EXPECT_FLOAT_EQ(p.height_step_min_rest_width_m, 0.8f);
  EXPECT_FLOAT_EQ(p.height_step_max_distance_m, 35.0f);
  EXPECT_FLOAT_EQ(p.depth_step_min_m, 1.2f);
  EXPECT_FLOAT_EQ(p.depth_step_min_px, 0.7f);
  EXPECT_FLOAT_EQ(p.depth_step_max_spread_px, 0.4f);
  EXPECT_FLOAT_EQ(p.depth_step_min_height_m, 1.4f);
  for (const char* key : {"height_step_min_m", "height_step_max_width_m", "height_step_min_height_m",
                          "height_step_max_height_m", "height_step_min_rest_stixels",
                          "height_step_min_rest_width_m", "height_step_max_distance_m", "depth_step_min_m",
                          "depth_step_min_px", "depth_step_max_spread_px", "depth_step_min_height_m"}) {
    expectRejected(key, -1.0);
  }
}

}  // namespace
}  // namespace nerv::stixel

// A lower road user in front of a taller one, chained into one group by a
// blended strip between them (nearer_fronts.hpp): the car gets its own box and
// the group's box stays the truck's; a near part as tall as the rest, or low
// as a bumper, gets none; the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>

#include "config.hpp"
#include "nearer_fronts.hpp"
#include "stixel_estimator.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

class stixelNearerFronts : public ::testing::Test {
 protected:
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);

  // A truck's rear at 24 m (3.3 m tall), a car 3 m in front of it covering its
  // right part up to car_top_m, and one strip between them that blends the
  // two (22.5 m), as the matcher's window does at the car's edge (highway seed
  // 31, frames 4-9: 16.5 px, 17.3 px, 18.2-19.4 px).
  FaceColumns paintTruckAndCar(double car_top_m) {
    paintFace(disp, scene, cam, 24.0f, 0.5, 3.0, 0.0, 3.3);
    paintFace(disp, scene, cam, 22.5f, 1.35, 1.55, 0.0, 3.3);
    return paintFace(disp, scene, cam, 21.0f, 1.55, 3.35, 0.0, car_top_m);
  }

  std::optional<Hypothesis> boxAt(const std::vector<Hypothesis>& hs, float z, float max_height_m) {
    for (const Hypothesis& h : hs)
      if (std::abs(h.z_m - z) < 1.0f && h.height_m <= max_height_m) return h;
    return std::nullopt;
  }
};

TEST_F(stixelNearerFronts, TheCarInFrontOfATruckGetsItsOwnBox) {
  const FaceColumns car = paintTruckAndCar(1.5);
  Params off;
  off.nearer_front_min_step_m = 0.0f;
  const StixelResult before = estimateStixels(disp, cam, off);
  ASSERT_FALSE(boxAt(before.hypotheses, 21.0f, 2.0f).has_value()) << "the scene must chain car and truck";
  bool tall = false;
  for (const Hypothesis& h : before.hypotheses) tall = tall || (h.height_m > 3.0f && h.box.x + h.box.w >= car.u1 - 3);
  ASSERT_TRUE(tall) << "one tall box over truck and car";

  const StixelResult r = estimateStixels(disp, cam, Params{});
  const std::optional<Hypothesis> c = boxAt(r.hypotheses, 21.0f, 2.0f);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->box.x, car.u0, 6);
  EXPECT_NEAR(c->box.x + c->box.w, car.u1, 3);
  EXPECT_NEAR(c->height_m, 1.5, 0.2);
  EXPECT_EQ(r.hypotheses.size(), before.hypotheses.size() + 1) << "the group's own box stays";
}

TEST_F(stixelNearerFronts, ANearPartAsTallAsTheRestGetsNone) {
  Params off, unlimited;
  off.nearer_front_min_step_m = 0.0f;
  unlimited.nearer_front_min_height_m = 0.0f;  // the control: without the height tests a box comes
  unlimited.nearer_front_min_rise_m = 0.0f;
  unlimited.nearer_front_max_height_m = 10.0f;
  for (const double top : {3.0}) {  // a near part nearly as tall as the truck
    disp = renderDisparity(scene, cam);
    paintTruckAndCar(top);
    const size_t without = estimateStixels(disp, cam, off).hypotheses.size();
    EXPECT_EQ(estimateStixels(disp, cam, Params{}).hypotheses.size(), without) << "near part " << top << " m tall";
    EXPECT_EQ(estimateStixels(disp, cam, unlimited).hypotheses.size(), without + 1) << "control, " << top << " m";
  }
}

TEST_F(stixelNearerFronts, ALowNearPartGetsNone) {
  // The function on a group made by hand: four far strips 3.3 m tall at 24 m,
  // four near ones at 21 m, first as tall as a car, then as a bumper.
  const GroundModel g = levelRoad(cam);
  ASSERT_TRUE(g.valid);
  auto stixelAt = [&](int u, double z, double top_m) { return stixelOnRoad(cam, u, z, top_m); };
  for (const double near_top : {1.5, 0.9}) {
    std::vector<Stixel> own;
    for (int k = 0; k < 4; ++k) own.push_back(stixelAt(600 + 5 * k, 24.0, 3.3));
    for (int k = 4; k < 8; ++k) own.push_back(stixelAt(600 + 5 * k, 21.0, near_top));
    std::vector<const Stixel*> group;
    for (const Stixel& s : own) group.push_back(&s);
    NearerFrontParams p;
    p.min_step_m = 1.0f;
    const std::vector<const Stixel*> front = findNearerFront(group, cam, g, p);
    if (near_top > 1.2) {
      ASSERT_EQ(front.size(), 4u);
      EXPECT_EQ(front.front()->u, 620);
    } else {
      EXPECT_TRUE(front.empty()) << "a bumper-high near part";
    }
  }
}

TEST_F(stixelNearerFronts, KeysAreReadAndRangeChecked) {
  YAML::Node root = YAML::Load(
      "stixel: {nearer_front_min_step_m: 1.5, nearer_front_min_step_px: 0.6, nearer_front_max_height_m: 2.5, "
      "nearer_front_min_height_m: 1.0, nearer_front_min_rise_m: 0.8}");
  ConfigSection top(root, "");
  ConfigSection s = top.section("stixel");
  const Params p = readParams(s);
  EXPECT_FLOAT_EQ(p.nearer_front_min_step_m, 1.5f);
  EXPECT_FLOAT_EQ(p.nearer_front_min_step_px, 0.6f);
  EXPECT_FLOAT_EQ(p.nearer_front_max_height_m, 2.5f);
  EXPECT_FLOAT_EQ(p.nearer_front_min_height_m, 1.0f);
  EXPECT_FLOAT_EQ(p.nearer_front_min_rise_m, 0.8f);
  YAML::Node bad = YAML::Load("stixel: {nearer_front_min_step_m: -1}");
  ConfigSection top2(bad, "");
  ConfigSection s2 = top2.section("stixel");
  EXPECT_THROW(readParams(s2), ConfigError);
}

}  // namespace
}  // namespace nerv::stixel

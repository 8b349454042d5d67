// Sign plates above an occluder (occluded_plates.hpp): a sign behind a parked car
// whose post the matcher lost above the roof gets a post at its plate's depth,
// from the roof up to the plate's top; a face 3 m wide at that height (a bridge,
// a crown), a plate with a taller, nearer body beside it (a truck), a lamp post
// that rises beyond the plate search, and a plate-sized patch just in front of
// the facade behind stay without one; the config keys.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "occluded_plates.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_scene_queries.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

Params ruleOff() {
  Params p;
  p.occluded_plate_max_top_m = 0.0f;
  return p;
}

// A facade at 40 m, a car (2 m wide, 1.5 m tall) at 15 m in front of it, and
// between them at 22 m what each test paints above the car's roof.
class stixelOccludedPlates : public ::testing::Test {
 protected:
  static constexpr float kCarZ = 15.0f, kSignZ = 22.0f, kWallZ = 40.0f;
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  FaceColumns car;
  int roof_row = 0;  // the car's top row

  void SetUp() override {
    paintFace(disp, scene, cam, kWallZ, -8.0, 8.0, 0.0, 8.0);
    car = paintFace(disp, scene, cam, kCarZ, -1.0, 1.0, 0.0, 1.5);
    roof_row = static_cast<int>(std::lround(footRow(scene, cam, kCarZ) - 1.5 * cam.fy / kCarZ));
  }

  int rowAt(float z, double height_m) const {
    return static_cast<int>(std::lround(footRow(scene, cam, z) - height_m * cam.fy / z));
  }

  // A sign at kSignZ: a 0.1 m post up to the plate [bottom_m, top_m] of width
  // width_m, the post's pixels between the car's roof and the plate lost (0).
  FaceColumns paintSign(double width_m, double bottom_m, double top_m) {
    const FaceColumns post = paintFace(disp, scene, cam, kSignZ, -0.05, 0.05, 0.0, bottom_m);
    disp(cv::Range(rowAt(kSignZ, bottom_m), roof_row), cv::Range(post.u0, post.u1)).setTo(0.0f);
    return paintFace(disp, scene, cam, kSignZ, -width_m / 2, width_m / 2, bottom_m, top_m);
  }
};

TEST_F(stixelOccludedPlates, ASignBehindACarGetsAPostFromTheRoofToItsPlate) {
  // urban seed 12: a sign at 20.8 m behind a car at 16.9 m, the facade at 35 m;
  // the post above the roof has almost no disparity, the plate at 3.1-3.6 m does.
  const FaceColumns plate = paintSign(0.6, 3.1, 3.6);
  ASSERT_LT(rowAt(kSignZ, 2.5), roof_row) << "the post is visible above the roof below the sky cut";

  EXPECT_FALSE(hypothesisAt(estimateStixels(disp, cam, ruleOff()).hypotheses, kSignZ, plate.u0, plate.u1))
      << "without the rule the strips above the roof go to the facade";

  const StixelResult on = estimateStixels(disp, cam, Params{});
  const std::optional<Hypothesis> h = hypothesisAt(on.hypotheses, kSignZ, plate.u0, plate.u1);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->box.y, rowAt(kSignZ, 3.6), 2) << "top: the plate's top";
  EXPECT_NEAR(h->box.y + h->box.h, roof_row, 2) << "bottom: the occluder's roof";
  EXPECT_NEAR(h->box.x, plate.u0, 3);
  EXPECT_NEAR(h->box.x + h->box.w, plate.u1, 3);
  // The post's strips replaced the facade's second-layer stixels there, not the car's.
  int at_sign = 0;
  for (const Stixel& s : on.stixels)
    if (s.u >= plate.u0 && s.u + s.width <= plate.u1 && std::abs(s.depth_m - kSignZ) < 1.0f) {
      ++at_sign;
      EXPECT_EQ(s.bottom_row, roof_row - 1);
    }
  EXPECT_GE(at_sign, 2);
  EXPECT_TRUE(hypothesisAt(on.hypotheses, kCarZ, car.u0, car.u1).has_value()) << "the car keeps its box";
}

TEST_F(stixelOccludedPlates, AFaceThreeMetresWideAtPlateHeightIsNoPlate) {
  // A bridge or a crown at the sign's depth: the columns 1 m beside are at its depth.
  const FaceColumns face = paintSign(3.0, 3.1, 3.6);
  EXPECT_FALSE(hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, kSignZ, face.u0, face.u1));
}

TEST_F(stixelOccludedPlates, ATallerBodyBesideThePlateIsNoBackground) {
  // highway seed 23: the upper rear of a truck above the part the first layer
  // took, beside it the truck's box nearer than the "plate": not a sign in
  // front of a background. Here a 4 m body at 18 m from 0.7 m to the right.
  const FaceColumns plate = paintSign(0.6, 3.1, 3.6);
  paintFace(disp, scene, cam, 18.0f, 0.7, 2.5, 0.0, 4.0);
  EXPECT_FALSE(hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, kSignZ, plate.u0, plate.u1));
}

TEST_F(stixelOccludedPlates, ALampPostRisingBeyondTheSearchIsNoPlate) {
  // A 0.3 m pole from the road to 7 m: its part above 3.1 m fills the strip and
  // has clear sides like a plate, but it does not end below the search's top.
  const FaceColumns pole = paintSign(0.3, 3.1, 7.0);
  EXPECT_FALSE(hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, kSignZ, pole.u0, pole.u1));
  // The same pole ending at 3.6 m is a plate on its post.
  disp = renderDisparity(scene, cam);
  SetUp();
  const FaceColumns sign = paintSign(0.3, 3.1, 3.6);
  EXPECT_TRUE(hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, kSignZ, sign.u0, sign.u1));
}

TEST_F(stixelOccludedPlates, APlateJustInFrontOfTheSecondLayerIsThatSurface) {
  // The plate 5 m in front of the facade behind it (occluded_plate_min_gap_m 6):
  // the spread of one surface (a pole's mount, matcher noise), not a sign.
  const float z = kWallZ - 5.0f;
  const FaceColumns plate = paintFace(disp, scene, cam, z, -0.3, 0.3, 3.1, 3.6);
  EXPECT_FALSE(hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, z, plate.u0, plate.u1));
  Params no_gap;
  no_gap.occluded_plate_min_gap_m = 0.0f;
  EXPECT_TRUE(hypothesisAt(estimateStixels(disp, cam, no_gap).hypotheses, z, plate.u0, plate.u1))
      << "found without the gap";
}

TEST(stixelOccludedPlatesKeys, AreReadAndRangeChecked) {
  expectFloatKeysRead({{"occluded_plate_max_top_m", &Params::occluded_plate_max_top_m},
                       {"occluded_plate_max_distance_m", &Params::occluded_plate_max_distance_m},
                       {"occluded_plate_max_occluder_m", &Params::occluded_plate_max_occluder_m},
                       {"occluded_plate_min_gap_m", &Params::occluded_plate_min_gap_m}},
                      {4.5, 35.0, 2.0, 5.0});
  expectRejected("occluded_plate_max_top_m", 25.0);
  EXPECT_EQ(Params{}.occluded_plate_max_top_m, 5.0f) << "on by default";
}

TEST(stixelOccludedPlatesKeys, ZeroTurnsTheRuleOff) {
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  std::vector<Stixel> first, behind;
  Stixel car;
  car.u = 600, car.width = 5, car.top_row = 180, car.bottom_row = 220;
  car.disparity = static_cast<float>(cam.disparityFromDepth(15.0));
  car.depth_m = 15.0f;
  first.push_back(car);
  paintFace(disp, scene, cam, 22.0f, -0.3, 0.3, 3.1, 3.6);
  const GroundModel g = estimateStixels(disp, cam, Params{}).ground;
  ASSERT_TRUE(g.valid);
  OccludedPlateParams p;
  p.plate.min_plate_bottom_m = 1.5f;
  p.max_plate_top_m = 5.0f;
  EXPECT_EQ(placeOccludedPlates(disp, cam, g, first, behind, StixelExtractionParams{}, p).size(), 1u);
  EXPECT_EQ(behind.size(), 1u);
  behind.clear();
  p.max_plate_top_m = 0.0f;
  EXPECT_TRUE(placeOccludedPlates(disp, cam, g, first, behind, StixelExtractionParams{}, p).empty());
  EXPECT_TRUE(behind.empty());
}

}  // namespace
}  // namespace nerv::stixel

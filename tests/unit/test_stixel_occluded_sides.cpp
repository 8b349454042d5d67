// Box sides over a nearer occluder (occluded_sides.hpp): a car parked behind
// a nearer one, seen beside it and as a band above its top, gets the band's
// width; a car that ends where the occluder begins keeps its own; a pedestrian-
// narrow post behind it is left alone; the config keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>
#include <string>

#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

std::optional<Hypothesis> hypothesisAt(const std::vector<Hypothesis>& hs, float z) {
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < 1.0f) return h;
  return std::nullopt;
}

// A flat road seen by the KITTI-like camera; each test paints its cars, the
// far one first (the near one is painted over it, as it occludes it).
class stixelOccludedSides : public ::testing::Test {
 protected:
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const float far_z = 29.0f, near_z = 22.0f;
};

TEST_F(stixelOccludedSides, ACarBehindANearerOneReachesOverItsRoofBand) {
  // Far car 2.6 m wide (its side seen obliquely), 1.5 m tall at 29 m; a 1.38 m
  // tall car at 22 m covers its right part from x = 1.0 m: 5 rows of the far
  // car's roof stay visible above it, too few for the column fill of the box
  // refinement.
  const FaceColumns far_car = paintFace(disp, scene, cam, far_z, -0.8, 1.8, 0.0, 1.5);
  const FaceColumns near_car = paintFace(disp, scene, cam, near_z, 1.0, 2.8, 0.0, 1.38);
  ASSERT_LT(near_car.u0, far_car.u1 - 10) << "the near car must hide a part of the far one";

  Params off;
  off.occluded_side_max_extension_m = 0.0f;
  const std::optional<Hypothesis> cut = hypothesisAt(estimateStixels(disp, cam, off).hypotheses, far_z);
  ASSERT_TRUE(cut.has_value());
  EXPECT_LE(cut->box.x + cut->box.w, near_car.u0 + 5) << "without the rule the box stops at the occluder";

  const StixelResult on = estimateStixels(disp, cam, Params{});
  const std::optional<Hypothesis> full = hypothesisAt(on.hypotheses, far_z);
  ASSERT_TRUE(full.has_value());
  EXPECT_NEAR(full->box.x + full->box.w, far_car.u1, 2) << "the box reaches the roof band's end";
  EXPECT_NEAR(full->box.x, cut->box.x, 1) << "the unoccluded side does not move";
  const std::optional<Hypothesis> occluder = hypothesisAt(on.hypotheses, near_z);
  ASSERT_TRUE(occluder.has_value());
  EXPECT_NEAR(occluder->box.x, near_car.u0, 2) << "the occluder's box is its own";
}

TEST_F(stixelOccludedSides, ACarEndingAtTheOccludersEdgeKeepsItsBox) {
  const FaceColumns far_car = paintFace(disp, scene, cam, far_z, -0.8, 1.0, 0.0, 1.5);
  paintFace(disp, scene, cam, near_z, 0.77, 2.6, 0.0, 1.38);
  const std::optional<Hypothesis> h = hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, far_z);
  ASSERT_TRUE(h.has_value());
  EXPECT_LE(h->box.x + h->box.w, far_car.u1 + 2) << "nothing at its depth above the occluder: no extension";
}

TEST_F(stixelOccludedSides, ABackgroundBandAtAnotherDepthIsNotTheObjects) {
  // Behind the far car's right part a wall at 45 m shows above the near car.
  paintFace(disp, scene, cam, 45.0f, 1.0, 4.0, 0.0, 3.0);
  const FaceColumns far_car = paintFace(disp, scene, cam, far_z, -0.8, 0.6, 0.0, 1.5);
  const FaceColumns near_car = paintFace(disp, scene, cam, near_z, 0.2, 2.8, 0.0, 1.38);
  ASSERT_LT(near_car.u0, far_car.u1);
  // The band test alone: the car-width prior (occluded_vehicles.hpp) would widen
  // this 1.4 m face's visible metre to a car's 1.8 m whatever the band holds.
  Params band_only;
  band_only.occluded_vehicle_width_m = 0.0f;
  const std::optional<Hypothesis> h = hypothesisAt(estimateStixels(disp, cam, band_only).hypotheses, far_z);
  ASSERT_TRUE(h.has_value());
  EXPECT_LE(h->box.x + h->box.w, far_car.u1 + 2) << "the wall above the occluder is not the car's roof";
}

TEST(stixelOccludedSidesKeys, AreReadAndRangeChecked) {
  YAML::Node n;
  n["occluded_side_max_extension_m"] = 1.5;
  n["occluded_side_min_width_m"] = 0.7;
  n["occluded_side_max_height_m"] = 3.0;
  n["occluded_side_min_step_m"] = 2.5;
  n["occluded_side_min_pixels"] = 3;
  n["occluded_side_min_fill"] = 0.4;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.occluded_side_max_extension_m, 1.5f);
  EXPECT_FLOAT_EQ(p.occluded_side_min_width_m, 0.7f);
  EXPECT_FLOAT_EQ(p.occluded_side_max_height_m, 3.0f);
  EXPECT_FLOAT_EQ(p.occluded_side_min_step_m, 2.5f);
  EXPECT_EQ(p.occluded_side_min_pixels, 3);
  EXPECT_FLOAT_EQ(p.occluded_side_min_fill, 0.4f);
  for (const char* key : {"occluded_side_max_extension_m", "occluded_side_min_width_m", "occluded_side_max_height_m",
                          "occluded_side_min_step_m", "occluded_side_min_pixels", "occluded_side_min_fill"}) {
    YAML::Node bad;
    bad[key] = -1;
    ConfigSection b(bad, "stixel");
    try {
      readParams(b);
      ADD_FAILURE() << key << " = -1 was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace nerv::stixel

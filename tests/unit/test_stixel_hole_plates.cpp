// Sign plates the matcher left as a hole (hole_plates.hpp): a post whose plate
// is an invalid hole bounded by a wall behind it gets the plate's rows and
// width; a post under open sky, under an opening wider than a plate, or a
// pedestrian-tall box keeps its own; a near plate cut by the image's top
// counts as closed; the config keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>
#include <vector>

#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

class stixelHolePlates : public ::testing::Test {
 protected:
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);

  // A 0.12 m post at z up to post_top_m, and above it the plate's rows
  // [post_top_m, plate_top_m] over [-half_m, half_m] left invalid.
  FaceColumns signWithHole(float z, double post_top_m, double plate_top_m, double half_m) {
    paintFace(disp, scene, cam, z, -0.06, 0.06, 0.0, post_top_m);
    const double foot = footRow(scene, cam, z), px = cam.fy / z;
    const FaceColumns cols = paintFace(disp, scene, cam, z, -half_m, half_m, post_top_m, plate_top_m);
    const int top = std::max(0, static_cast<int>(std::lround(foot - plate_top_m * px)));
    const int bottom = static_cast<int>(std::lround(foot - post_top_m * px));
    disp(cv::Range(top, bottom), cv::Range(cols.u0, cols.u1)).setTo(0.0f);
    return cols;
  }
  Params off() const {
    Params p;
    p.hole_plate_max_width_m = 0.0f;
    return p;
  }
};

TEST_F(stixelHolePlates, APlateLeftAsAHoleBeforeAWallRaisesAndWidensItsPostsBox) {
  // urban seed 14 frame 10: a sign at 16 m before a facade at 26 m, its post
  // found up to 2.7 m, its 0.6 m plate at 2.7-3.5 m invalid.
  const float z = 16.0f;
  paintFace(disp, scene, cam, 26.0f, -4.0, 4.0, 0.0, 8.0);
  const FaceColumns plate = signWithHole(z, 2.7, 3.5, 0.3);
  const double foot = footRow(scene, cam, z), px = cam.fy / z;

  const std::optional<Hypothesis> before = postAt(estimateStixels(disp, cam, off()).hypotheses, z, 2.0f);
  ASSERT_TRUE(before.has_value());
  EXPECT_NEAR(before->box.y, foot - 2.7 * px, 3) << "without the rule: the post's top";
  EXPECT_LT(before->box.w, (plate.u1 - plate.u0) / 2);

  const std::optional<Hypothesis> after = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z, 2.0f);
  ASSERT_TRUE(after.has_value());
  EXPECT_NEAR(after->box.y, foot - 3.5 * px, 2) << "the plate's top";
  EXPECT_NEAR(after->box.x, plate.u0, 1);
  EXPECT_NEAR(after->box.x + after->box.w, plate.u1, 1);
}

TEST_F(stixelHolePlates, APostUnderOpenSkyOrAWideOpeningKeepsItsBox) {
  const float z = 16.0f;
  // Nothing behind the post: the hole above it is the sky (no disparity up to
  // the image's top, beyond the 2 m a plate may span).
  {
    signWithHole(z, 2.7, 3.5, 0.3);
    const std::optional<Hypothesis> h = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z, 2.0f);
    ASSERT_TRUE(h.has_value());
    EXPECT_NEAR(h->box.y, footRow(scene, cam, z) - 2.7 * cam.fy / z, 3);
  }
  // A wall with a 1.6 m opening above the post: wider than a plate.
  disp = renderDisparity(scene, cam);
  paintFace(disp, scene, cam, 26.0f, -4.0, 4.0, 0.0, 8.0);
  signWithHole(z, 2.7, 3.5, 0.8);
  const std::optional<Hypothesis> h = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z, 2.0f);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->box.y, footRow(scene, cam, z) - 2.7 * cam.fy / z, 3);
  EXPECT_LT(h->box.w, 10);
}

TEST_F(stixelHolePlates, APedestrianTallBoxUnderAHoleKeepsItsTop) {
  // 1.3 m tall (below the 1.5 m a post's top must reach) under a bounded hole.
  const float z = 16.0f;
  paintFace(disp, scene, cam, 26.0f, -4.0, 4.0, 0.0, 8.0);
  paintFace(disp, scene, cam, z, -0.2, 0.2, 0.0, 1.3);
  const double foot = footRow(scene, cam, z), px = cam.fy / z;
  const FaceColumns hole = paintFace(disp, scene, cam, z, -0.2, 0.2, 1.3, 1.8);
  disp(cv::Range(static_cast<int>(std::lround(foot - 1.8 * px)), static_cast<int>(std::lround(foot - 1.3 * px))),
       cv::Range(hole.u0, hole.u1))
      .setTo(0.0f);
  const std::optional<Hypothesis> h = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z, 1.0f);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->box.y, foot - 1.3 * px, 3);
}

TEST_F(stixelHolePlates, ANearPlateCutByTheImageTopIsClosed) {
  // A sign at 7 m before a wall at 12 m: post up to 3.0 m, plate hole from 3.0 m
  // into the image's top row (urban seed 14 frames 1-3, signs at 7-9 m).
  const float z = 7.0f;
  paintFace(disp, scene, cam, 12.0f, -4.0, 4.0, 0.0, 8.0);
  const double foot = footRow(scene, cam, z), px = cam.fy / z;
  ASSERT_LT(foot - 3.6 * px, 0.0) << "the plate must reach beyond the image's top";
  const FaceColumns plate = signWithHole(z, 3.0, 3.6, 0.3);
  const std::optional<Hypothesis> before = postAt(estimateStixels(disp, cam, off()).hypotheses, z, 2.0f);
  ASSERT_TRUE(before.has_value());
  EXPECT_GT(before->box.y, 10);
  const std::optional<Hypothesis> after = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z, 2.0f);
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(after->box.y, 0);
  EXPECT_NEAR(after->box.x, plate.u0, 1);
}

TEST_F(stixelHolePlates, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"hole_plate_max_width_m", &Params::hole_plate_max_width_m},
                       {"hole_plate_min_top_m", &Params::hole_plate_min_top_m},
                       {"hole_plate_min_height_m", &Params::hole_plate_min_height_m},
                       {"hole_plate_max_height_m", &Params::hole_plate_max_height_m},
                       {"hole_plate_max_hole_width_m", &Params::hole_plate_max_hole_width_m},
                       {"hole_plate_min_share", &Params::hole_plate_min_share}},
                      {0.5, 1.6, 0.2, 1.5, 1.1, 0.8});
  expectRejected("hole_plate_min_share", 1.5);
  expectRejected("hole_plate_max_width_m", -0.1);
  EXPECT_FLOAT_EQ(Params{}.hole_plate_max_width_m, 0.7f);
}

}  // namespace
}  // namespace nerv::stixel


// A road user cut off at the matcher's blend in the background gap beside it
// (gap_strips.hpp): on rendered disparity a cyclist at 30 m, a 0.4 m gap that
// reads 1.2 m behind it (the blend a real matcher makes there) and a parked
// car at the cyclist's depth are one group and one box without the rule, the
// cyclist's box is tightened to its own columns with it; a car's rear and a
// post beside such a gap keep their width; at 36 m, a gap reading only 0.35 px
// behind a cyclist standing on the road is cut with the finer end dip, the same
// dip beside an end seen above an occluder is not; the keys.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_scene_queries.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// A flat road seen by the KITTI-like camera, the rule on and off; each test
// paints its objects.
struct GapScene {
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  std::vector<Hypothesis> with(float min_dip_px) const {
    Params p;
    p.gap_strip_min_dip_px = min_dip_px;
    return estimateStixels(disp, cam, p).hypotheses;
  }
};

TEST(stixelGapStrips, ACyclistsBoxStopsAtTheGapBesideAParkedCar) {
  // Cyclist 0.6 m wide at 30 m (13.0 px), 1.6 m tall as the matcher leaves
  // it (its head lost to the background: too little above the car for the
  // height step); the 0.4 m gap to the car's rear reads 31.2 m (12.5 px: 0.5
  // px and 1.2 m behind both, within the grouping's 1.5 m gap); car 1.8 m
  // wide, 1.45 m tall at 30 m.
  GapScene t;
  const FaceColumns cyclist = paintFace(t.disp, t.scene, t.cam, 30.0f, 0.0, 0.6, 0.0, 1.6);
  paintFace(t.disp, t.scene, t.cam, 31.2f, 0.6, 1.0, 0.0, 1.45);
  const FaceColumns car = paintFace(t.disp, t.scene, t.cam, 30.0f, 1.0, 2.8, 0.0, 1.45);

  const std::optional<Hypothesis> merged = hypothesisAt(t.with(0.0f), 30.0f, cyclist.u0, cyclist.u1);
  ASSERT_TRUE(merged.has_value());
  EXPECT_GT(merged->box.x + merged->box.w, cyclist.u1 + 10) << "off: the box runs over the gap onto the car";

  const std::vector<Hypothesis> hs = estimateStixels(t.disp, t.cam, Params{}).hypotheses;
  const std::optional<Hypothesis> rider = hypothesisAt(hs, 30.0f, cyclist.u0, cyclist.u1);
  ASSERT_TRUE(rider.has_value());
  EXPECT_NEAR(rider->box.x, cyclist.u0, 3);
  EXPECT_NEAR(rider->box.x + rider->box.w, cyclist.u1, 3) << "the box ends at the cyclist's own right edge";
  EXPECT_NEAR(rider->height_m, 1.6f, 0.15f);
  const std::optional<Hypothesis> parked = hypothesisAt(hs, 30.0f, car.u1 - 5, car.u1);
  ASSERT_TRUE(parked.has_value()) << "the car keeps a box of its own";
  EXPECT_NEAR(parked->box.x, car.u0, 5);
  EXPECT_NEAR(parked->box.x + parked->box.w, car.u1, 5);
}

TEST(stixelGapStrips, ACarsRearBesideAGapKeepsItsWidth) {
  // The same gap and a second car: a 1.8 m rear is no road user's end.
  GapScene t;
  const FaceColumns car = paintFace(t.disp, t.scene, t.cam, 30.0f, -1.2, 0.6, 0.0, 1.45);
  paintFace(t.disp, t.scene, t.cam, 31.2f, 0.6, 1.0, 0.0, 1.45);
  paintFace(t.disp, t.scene, t.cam, 30.0f, 1.0, 2.8, 0.0, 1.45);
  const std::optional<Hypothesis> a = hypothesisAt(t.with(0.0f), 30.0f, car.u0, car.u0 + 5);
  const std::optional<Hypothesis> b = hypothesisAt(t.with(Params{}.gap_strip_min_dip_px), 30.0f, car.u0, car.u0 + 5);
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(a->box.x, b->box.x);
  EXPECT_EQ(a->box.w, b->box.w);
}

TEST(stixelGapStrips, APostBesideAGapKeepsItsBox) {
  // A 0.12 m post, 1.8 m tall at 20 m, with a farther blend band beside it:
  // one strip is no end of a road user.
  GapScene t;
  const FaceColumns post = paintFace(t.disp, t.scene, t.cam, 20.0f, 0.0, 0.12, 0.0, 1.8);
  paintFace(t.disp, t.scene, t.cam, 20.9f, 0.12, 0.45, 0.0, 1.8);
  const std::vector<Hypothesis> a = t.with(0.0f), b = t.with(Params{}.gap_strip_min_dip_px);
  ASSERT_EQ(a.size(), b.size());
  const std::optional<Hypothesis> ha = hypothesisAt(a, 20.0f, post.u0, post.u1),
                                  hb = hypothesisAt(b, 20.0f, post.u0, post.u1);
  ASSERT_TRUE(ha.has_value());
  ASSERT_TRUE(hb.has_value());
  EXPECT_EQ(ha->box.x, hb->box.x);
  EXPECT_EQ(ha->box.w, hb->box.w);
}

// Cyclist 0.6 m wide, 1.6 m tall at 36 m (10.7 px); beside it a 0.5 m gap
// reading 37.2 m (0.35 px and 1.2 m behind it: below gap_strip_min_dip_px,
// what a parked car a car length behind reads at 30-40 m); then a car's rear
// at 35.8 m, 0.4 px nearer than the gap (the row's next car, urban seed 11).
// occluded: a car's rear 1 m tall at 20 m hides the lower part of the
// cyclist's columns (then its stixels end at the occluder's top, off the road).
struct FarGapScene : GapScene {
  FaceColumns rider, car;
  explicit FarGapScene(bool occluded) {
    rider = paintFace(disp, scene, cam, 36.0f, 0.0, 0.6, 0.0, 1.6);
    paintFace(disp, scene, cam, 37.2f, 0.6, 1.1, 0.0, 1.45);
    car = paintFace(disp, scene, cam, 35.8f, 1.1, 2.9, 0.0, 1.45);
    if (occluded) paintFace(disp, scene, cam, 20.0f, -1.5, 0.35, 0.0, 1.0);
  }
  std::vector<Hypothesis> withEndDip(float min_end_dip_px) const {
    Params p;
    p.gap_strip_min_end_dip_px = min_end_dip_px;
    return estimateStixels(disp, cam, p).hypotheses;
  }
};

TEST(stixelGapStrips, AFarCyclistIsCutAtAShallowGapWithTheFinerEndDip) {
  FarGapScene t(false);
  const std::optional<Hypothesis> merged = hypothesisAt(t.withEndDip(0.0f), 36.0f, t.rider.u0, t.rider.u1);
  ASSERT_TRUE(merged.has_value());
  EXPECT_GT(merged->box.x + merged->box.w, t.rider.u1 + 8) << "min_dip_px alone: the box runs onto the car";
  const std::optional<Hypothesis> rider =
      hypothesisAt(t.withEndDip(Params{}.gap_strip_min_end_dip_px), 36.0f, t.rider.u0, t.rider.u1);
  ASSERT_TRUE(rider.has_value());
  EXPECT_NEAR(rider->box.x, t.rider.u0, 3);
  EXPECT_NEAR(rider->box.x + rider->box.w, t.rider.u1, 3) << "the box ends at the cyclist's own right edge";
}

TEST(stixelGapStrips, AnEndAboveAnOccluderKeepsTheCoarseDip) {
  // The same columns seen above a nearer car (as a van's top is): the end
  // does not stand on the road, the finer dip does not apply.
  FarGapScene t(true);
  const std::vector<Hypothesis> a = t.withEndDip(0.0f), b = t.withEndDip(Params{}.gap_strip_min_end_dip_px);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].box.x, b[i].box.x);
    EXPECT_EQ(a[i].box.w, b[i].box.w);
  }
}

TEST(stixelGapStripsKeys, AreReadAndRangeChecked) {
  expectFloatKeysRead({{"gap_strip_min_dip_px", &Params::gap_strip_min_dip_px},
                       {"gap_strip_min_dip_m", &Params::gap_strip_min_dip_m},
                       {"gap_strip_max_gap_m", &Params::gap_strip_max_gap_m},
                       {"gap_strip_max_end_width_m", &Params::gap_strip_max_end_width_m},
                       {"gap_strip_min_height_m", &Params::gap_strip_min_height_m},
                       {"gap_strip_max_height_m", &Params::gap_strip_max_height_m},
                       {"gap_strip_max_spread_px", &Params::gap_strip_max_spread_px},
                       {"gap_strip_min_end_dip_px", &Params::gap_strip_min_end_dip_px},
                       {"gap_strip_max_end_foot_gap_m", &Params::gap_strip_max_end_foot_gap_m}},
                      {0.5, 1.0, 0.4, 0.9, 1.5, 2.0, 0.4, 0.25, 0.2});
  expectRejected("gap_strip_min_end_dip_px", 101.0);
  expectRejected("gap_strip_max_end_foot_gap_m", 11.0);
  expectRejected("gap_strip_min_dip_px", 101.0);
  expectRejected("gap_strip_max_gap_m", 11.0);
}

}  // namespace
}  // namespace nerv::stixel

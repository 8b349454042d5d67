// A background gap narrower than a strip (gap_columns.hpp): a cyclist beside
// the near end of a van's receding side is cut off at the gap column by
// column; a dip inside a van's flat rear is no gap (the far side is the same
// surface), unless what follows it differs in height; a car's side receding
// to the group's end is no gap; a dip inside a far pedestrian is not cut; the
// rule switched off; the keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gap_columns.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

class stixelGapColumns : public ::testing::Test {
 protected:
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const GroundModel g = levelRoad(cam);
  std::vector<Stixel> own;

  void addStixel(int u, double z, double top_m) { own.push_back(stixelOnRoad(cam, u, z, top_m)); }
  std::vector<const Stixel*> group() const {
    std::vector<const Stixel*> out;
    for (const Stixel& s : own) out.push_back(&s);
    return out;
  }
  static GapColumnParams on() {
    GapColumnParams p;
    p.min_dip_px = 0.3f;
    p.ends.min_dip_m = 0.75f;
    return p;
  }
};

// Urban seeds 13 and 14: a cyclist at 30.5 m, 0.5 m beside the near end of
// a parked van's left side, a facade at 36 m seen through the gap.
TEST_F(stixelGapColumns, ACyclistIsCutOffAtTheGapBesideAVansSide) {
  ASSERT_TRUE(g.valid);
  paintFace(disp, scene, cam, 36.0f, 1.0, 5.0, 0.0, 4.0);
  const FaceColumns cyclist = paintFace(disp, scene, cam, 30.5f, 2.0, 2.6, 0.0, 1.8);
  // The van's side recedes from 30.5 m to 26 m over columns right of the gap.
  const double side_x = 3.0;
  int side_u0 = -1;
  for (double z = 30.5; z > 26.0; z -= 0.5) {
    const FaceColumns c = paintFace(disp, scene, cam, static_cast<float>(z), side_x * z / 30.5,
                                    side_x * (z + 0.5) / 30.5 + 0.02, 0.0, 2.4);
    if (side_u0 < 0 || c.u0 < side_u0) side_u0 = c.u0;
  }
  ASSERT_GT(side_u0, cyclist.u1 + 5) << "a gap of more than a strip between them";
  // The grouping's strips: three on the cyclist, the one over the gap read at
  // the cyclist's depth (the matcher's blend), one on the side's near end.
  for (int k = 0; k < 4; ++k) addStixel(cyclist.u0 + 5 * k, 30.5, 1.8);
  addStixel(cyclist.u0 + 20, 30.0, 2.4);
  const GapCut c = findGapColumns(group(), disp, cam, g, on());
  ASSERT_TRUE(c.found);
  EXPECT_GE(c.lo, cyclist.u1 - 1);
  EXPECT_LE(c.lo, cyclist.u1 + 1);
  for (int k = 0; k < 3; ++k) EXPECT_LT(own[static_cast<size_t>(k)].u, c.lo) << "the cyclist's strips stay on its side";

  GapColumnParams off = on();
  off.min_dip_px = 0.0f;
  EXPECT_FALSE(findGapColumns(group(), disp, cam, g, off).found);
}

TEST_F(stixelGapColumns, ADipInsideAFlatRearIsNoGapUnlessWhatFollowsDiffersInHeight) {
  // A van's rear at 33 m, 2 m wide and 1.9 m tall, reading 4 m farther over
  // three columns 0.7 m from its left end (an untextured patch).
  const FaceColumns van = paintFace(disp, scene, cam, 33.0f, 1.0, 3.0, 0.0, 1.9);
  const int dip0 = van.u0 + 15;  // at a strip's left edge, 0.69 m from the van's
  const FaceColumns dip = paintFace(disp, scene, cam, 37.0f, (dip0 - cam.cx) * 37.0 / cam.fx,
                                    (dip0 + 3 - cam.cx) * 37.0 / cam.fx, 0.0, 1.9 * 37.0 / 33.0);
  ASSERT_EQ(dip.u0, dip0);
  for (int u = van.u0; u + 5 <= van.u1; u += 5) addStixel(u, 33.0, 1.9);
  EXPECT_FALSE(findGapColumns(group(), disp, cam, g, on()).found) << "the far side is the same surface";
  // The same dip, but the strips after it stand 0.5 m lower (another object
  // at the same depth, a car beside a cyclist): cut.
  for (Stixel& s : own)
    if (s.u >= dip0) s.top_row = stixelOnRoad(cam, s.u, 33.0, 1.4).top_row;
  EXPECT_TRUE(findGapColumns(group(), disp, cam, g, on()).found);
}

TEST_F(stixelGapColumns, ASideRecedingToTheGroupsEndIsNoGap) {
  // Wet_road seed 9: a car's rear at 22 m and its left side receding to 26 m
  // at the group's left end. From the rear's right end the side reads
  // farther and farther up to the group's end: no far side rises again.
  int side_u0 = disp.cols;
  for (double z = 26.0; z > 22.0; z -= 0.5) {  // the side, 1 m right of the camera, far to near
    const FaceColumns c = paintFace(disp, scene, cam, static_cast<float>(z), 0.92, 1.0, 0.0, 1.5);
    side_u0 = std::min(side_u0, c.u0);
  }
  const FaceColumns rear = paintFace(disp, scene, cam, 22.0f, 1.0, 2.8, 0.0, 1.5);
  ASSERT_LT(side_u0, rear.u0 - 3);
  for (int u = side_u0; u < rear.u0; u += 5) addStixel(u, 23.5, 1.5);
  for (int u = rear.u0; u + 5 <= rear.u1; u += 5) addStixel(u, 22.0, 1.5);
  EXPECT_FALSE(findGapColumns(group(), disp, cam, g, on()).found);
}

TEST_F(stixelGapColumns, ADipInsideAFarPedestrianIsNotCut) {
  // Urban seed 13 on the rendered disparity, 36-38 m: the facade shows
  // between a pedestrian's arm and body, 4 columns inside the right edge of
  // its two strips, and a van's side rises right after it.
  paintFace(disp, scene, cam, 45.0f, 0.0, 4.0, 0.0, 4.0);
  const FaceColumns person = paintFace(disp, scene, cam, 35.0f, 1.0, 1.0 + 10 * 35.0 / cam.fx, 0.0, 1.7);
  ASSERT_EQ(person.u1 - person.u0, 10);
  const int arm = person.u1 - 4;
  paintFace(disp, scene, cam, 45.0f, (arm - cam.cx) * 45.0 / cam.fx, (arm + 1 - cam.cx) * 45.0 / cam.fx, 0.0, 1.7 * 45.0 / 35.0);
  for (double z = 35.0; z > 31.0; z -= 0.5)  // the side, from the person's edge on, nearer to the right
    paintFace(disp, scene, cam, static_cast<float>(z), (person.u1 + (35.0 - z) * 2 - cam.cx) * z / cam.fx,
              (person.u1 + (35.0 - z) * 2 + 1 - cam.cx) * z / cam.fx, 0.0, 2.4);
  addStixel(person.u0, 35.0, 1.7);
  addStixel(person.u0 + 5, 35.0, 1.7);
  addStixel(person.u0 + 10, 34.0, 2.4);
  addStixel(person.u0 + 15, 32.5, 2.4);
  EXPECT_FALSE(findGapColumns(group(), disp, cam, g, on()).found);
  GapColumnParams deep = on();
  deep.max_inside_px = 10;  // control: allowed that deep, the dip cuts the pedestrian
  const GapCut c = findGapColumns(group(), disp, cam, g, deep);
  ASSERT_TRUE(c.found);
  EXPECT_LT(c.lo, person.u1 - 2);
}

TEST_F(stixelGapColumns, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"gap_column_min_dip_px", &Params::gap_column_min_dip_px},
                       {"gap_column_min_rise_px", &Params::gap_column_min_rise_px},
                       {"gap_column_min_background_m", &Params::gap_column_min_background_m}},
                      {0.5, 0.6, 3.0});
}

}  // namespace
}  // namespace nerv::stixel

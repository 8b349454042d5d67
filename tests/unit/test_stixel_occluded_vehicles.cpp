// A car partly hidden behind a nearer one, widened to a car's width
// (occluded_vehicles.hpp): the hidden side is the one the occluder meets, the
// box stops at the occluder's far edge; a box narrower than a car's visible
// part (a far pedestrian), one with occluders on both sides, one beside an
// object at its own depth and a car seen whole keep their boxes; the keys.
#include <gtest/gtest.h>

#include <vector>

#include "occluded_vehicles.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// A hypothesis with box columns [x0, x1) and rows [y0, y1) at depth z.
Hypothesis hyp(int id, int x0, int x1, int y0, int y1, float z, const StereoCamera& cam) {
  Hypothesis h;
  h.id = id;
  h.box = {x0, y0, x1 - x0, y1 - y0};
  h.z_m = z;
  h.width_m = static_cast<float>((x1 - x0) * z / cam.fx);
  h.height_m = static_cast<float>((y1 - y0) * z / cam.fy);
  h.x_m = static_cast<float>((0.5 * (x0 + x1) - cam.cx) * z / cam.fx);
  return h;
}

OccludedVehicleParams defaults() { return occludedVehicleParams(Params{}); }

// wet_road seed 7 frame 3: a parked car at 31.6 m, box u 673-699 (1.14 m) of
// its 1.8 m, rows 171-203; the next car of the row 8 m nearer begins at its
// right side (u 694) and covers its rows.
TEST(stixelOccludedVehicles, AParkedCarBehindANearerOneGetsACarsWidthOnItsHiddenSide) {
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Hypothesis> hs = {hyp(1, 673, 699, 171, 204, 31.6f, cam), hyp(2, 694, 760, 170, 225, 23.5f, cam)};
  widenOccludedVehicles(hs, cam, OccludedVehicleParams{});  // off by default in the struct
  EXPECT_EQ(hs[0].box.w, 26);
  widenOccludedVehicles(hs, cam, defaults());
  const int want = static_cast<int>(std::lround(1.8 * cam.fx / 31.6));
  EXPECT_EQ(hs[0].box.x, 673) << "the visible side stays";
  EXPECT_EQ(hs[0].box.w, want);
  EXPECT_NEAR(hs[0].width_m, 1.8f, 0.03f);
  EXPECT_NEAR(hs[0].x_m, (673 + 0.5 * want - cam.cx) * 31.6 / cam.fx, 1e-3);
  EXPECT_EQ(hs[1].box.w, 66) << "the occluder keeps its box";

  // Mirrored: the occluder on the left widens the left side.
  std::vector<Hypothesis> m = {hyp(1, 500, 526, 171, 204, 31.6f, cam), hyp(2, 440, 505, 170, 225, 23.5f, cam)};
  widenOccludedVehicles(m, cam, defaults());
  EXPECT_EQ(m[0].box.x + m[0].box.w, 526);
  EXPECT_EQ(m[0].box.x, 526 - want);
}

TEST(stixelOccludedVehicles, TheBoxStopsAtTheOccludersFarEdge) {
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Hypothesis> hs = {hyp(1, 673, 699, 171, 204, 31.6f, cam), hyp(2, 694, 705, 150, 225, 23.5f, cam)};
  widenOccludedVehicles(hs, cam, defaults());
  EXPECT_EQ(hs[0].box.x + hs[0].box.w, 705);
}

TEST(stixelOccludedVehicles, OtherBoxesKeepTheirWidth) {
  const StereoCamera cam = kittiLikeCamera();
  const Hypothesis occluder = hyp(2, 694, 760, 170, 225, 23.5f, cam);
  struct Case {
    const char* what;
    std::vector<Hypothesis> hs;
  };
  const Case cases[] = {
      // urban seed 13: far pedestrians' boxes, widened by the matcher's fattening to 0.9-1.06 m.
      {"a far pedestrian 1.0 m wide", {hyp(1, 676, 699, 165, 202, 31.6f, cam), occluder}},
      {"occluders on both sides", {hyp(1, 673, 699, 171, 204, 31.6f, cam), occluder, hyp(3, 600, 678, 170, 225, 23.5f, cam)}},
      {"a neighbour at its own depth", {hyp(1, 673, 699, 171, 204, 31.6f, cam), hyp(2, 694, 740, 168, 204, 30.5f, cam)}},
      {"a car seen whole (1.7 m)", {hyp(1, 660, 699, 171, 204, 31.6f, cam), occluder}},
      {"a van (2.2 m tall)", {hyp(1, 673, 699, 155, 204, 31.6f, cam), occluder}},
      {"an occluder that leaves its lower rows free", {hyp(1, 673, 699, 171, 204, 31.6f, cam), hyp(2, 694, 760, 120, 190, 23.5f, cam)}},
  };
  for (const Case& c : cases) {
    std::vector<Hypothesis> hs = c.hs;
    widenOccludedVehicles(hs, cam, defaults());
    EXPECT_EQ(hs[0].box.x, c.hs[0].box.x) << c.what;
    EXPECT_EQ(hs[0].box.w, c.hs[0].box.w) << c.what;
  }
}

TEST(stixelOccludedVehicles, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"occluded_vehicle_width_m", &Params::occluded_vehicle_width_m},
                       {"occluded_vehicle_min_width_m", &Params::occluded_vehicle_min_width_m},
                       {"occluded_vehicle_max_width_m", &Params::occluded_vehicle_max_width_m},
                       {"occluded_vehicle_min_height_m", &Params::occluded_vehicle_min_height_m},
                       {"occluded_vehicle_max_height_m", &Params::occluded_vehicle_max_height_m},
                       {"occluded_vehicle_min_step_m", &Params::occluded_vehicle_min_step_m}},
                      {1.7, 1.0, 1.5, 1.1, 2.0, 3.0});
  expectRejected("occluded_vehicle_width_m", 6.0);
  EXPECT_FLOAT_EQ(Params{}.occluded_vehicle_width_m, 1.8f);
}

}  // namespace
}  // namespace nerv::stixel

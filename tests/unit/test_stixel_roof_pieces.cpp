// Pieces stacked on a vehicle's roof line (roof_pieces.hpp): a thin strip of
// upper-layer stixels a few metres behind a car's rear, standing on its
// stixels and inside its box, is dropped; a pedestrian behind the car seen
// over its roof, a pedestrian beside it, a post in front of a hedge and one
// behind it keep their boxes; the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "hypothesis_grouping.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// A stixel at depth z from top_row to bottom_row.
Stixel rowsAt(const StereoCamera& cam, int u, float z, int top_row, int bottom_row) {
  Stixel s;
  s.u = u, s.width = 5, s.depth_m = z;
  s.disparity = static_cast<float>(cam.disparityFromDepth(z));
  s.top_row = top_row, s.bottom_row = bottom_row;
  return s;
}

void sortByU(std::vector<Stixel>& st) {
  std::stable_sort(st.begin(), st.end(), [](const Stixel& a, const Stixel& b) { return a.u < b.u; });
}

// kitti_raw_0926_seq frame 6: a car at 25.5 m (u 335-410, 1.45 m), whose
// strips u 360-370 end lower (1.15 m: the rear window reads farther); above
// them, up to the car's roof row, stixels at 27.7 m.
constexpr float kCarZ = 25.5f;
std::vector<Stixel> car(const StereoCamera& cam) {
  std::vector<Stixel> st;
  for (int k = 0; k < 15; ++k) {
    const int u = 335 + 5 * k;
    st.push_back(stixelAt(cam, u, kCarZ, u >= 360 && u <= 370 ? 1.15f : 1.45f));
  }
  return st;
}
int roofRow(const StereoCamera& cam) { return stixelAt(cam, 0, kCarZ, 1.45f).top_row; }

// Upper-layer stixels on strips u 360-370 from top_row down to the car's stixel there.
void addOnTop(const StereoCamera& cam, std::vector<Stixel>& st, float z, int top_row) {
  const int under = stixelAt(cam, 0, kCarZ, 1.15f).top_row;
  for (int u = 360; u <= 370; u += 5) st.push_back(rowsAt(cam, u, z, top_row, under - 1));
  sortByU(st);
}

GroupingParams defaults() {
  GroupingParams p;
  p.roof_pieces = roofPieceParams(Params{});
  return p;
}

TEST(stixelRoofPieces, AStripOnACarsRoofLineIsDropped) {
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Stixel> st = car(cam);
  addOnTop(cam, st, 27.7f, roofRow(cam));
  GroupingParams off = defaults();
  off.roof_pieces.max_stixels = 0;
  off.side_slivers.max_stixels = 0;
  ASSERT_EQ(groupStixels(st, cam, off).size(), 2u) << "without the rule the strip is a box of its own";

  GroupingParams on = defaults();
  on.side_slivers.max_stixels = 0;
  const auto hs = groupStixels(st, cam, on);
  ASSERT_EQ(hs.size(), 1u);
  EXPECT_EQ(hs[0].box.x, 335);
  EXPECT_EQ(hs[0].box.x + hs[0].box.w, 410);
  EXPECT_EQ(hs[0].box.y, roofRow(cam)) << "the car's box already covers the strip";
  EXPECT_EQ(hs[0].num_stixels, 15);
}

TEST(stixelRoofPieces, APedestrianBehindTheCarSeenOverItsRoofKeepsItsBox) {
  // 1.75 m tall 2 m behind the car: 0.3 m of her sticks out above the roof.
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Stixel> st = car(cam);
  addOnTop(cam, st, 27.5f, stixelAt(cam, 0, 27.5f, 1.75f).top_row);
  EXPECT_EQ(groupStixels(st, cam, defaults()).size(), 2u);
  // Farther than a car's length behind it: another object.
  st = car(cam);
  addOnTop(cam, st, 33.0f, roofRow(cam));
  EXPECT_EQ(groupStixels(st, cam, defaults()).size(), 2u);
}

TEST(stixelRoofPieces, APedestrianBesideTheCarKeepsItsBox) {
  // On the road beside the car, 2 m farther, 1.75 m tall: not on the car's stixels.
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Stixel> st = car(cam);
  for (int k = 0; k < 3; ++k) st.push_back(stixelAt(cam, 410 + 5 * k, 27.5f, 1.75f));
  sortByU(st);
  EXPECT_EQ(groupStixels(st, cam, defaults()).size(), 2u);
}

// A box of its own on the post's strips u 335-345.
bool hasPostBox(const std::vector<Hypothesis>& hs) {
  return std::any_of(hs.begin(), hs.end(), [](const Hypothesis& h) { return h.box.x == 335 && h.box.w == 10; });
}

TEST(stixelRoofPieces, APostBeforeOrBehindAHedgeKeepsItsBox) {
  const StereoCamera cam = kittiLikeCamera();
  // A hedge 1.1 m tall at 12 m, u 300-375.
  auto hedge = [&] {
    std::vector<Stixel> st;
    for (int k = 0; k < 16; ++k) st.push_back(stixelAt(cam, 300 + 5 * k, 12.0f, 1.1f));
    return st;
  };
  // A post 2.5 m tall at 10 m in front of it, standing on the road (its stixels replace the hedge's).
  std::vector<Stixel> st = hedge();
  st.erase(std::remove_if(st.begin(), st.end(), [](const Stixel& s) { return s.u == 335 || s.u == 340; }), st.end());
  for (int u : {335, 340}) st.push_back(stixelAt(cam, u, 10.0f, 2.5f, 260));
  sortByU(st);
  EXPECT_TRUE(hasPostBox(groupStixels(st, cam, defaults()))) << "post in front of the hedge";
  // A post behind it at 14 m, seen over its top up to 2.5 m.
  st = hedge();
  const int hedge_top = stixelAt(cam, 0, 12.0f, 1.1f).top_row;
  for (int u : {335, 340}) st.push_back(rowsAt(cam, u, 14.0f, stixelAt(cam, 0, 14.0f, 2.5f, 230).top_row, hedge_top - 1));
  sortByU(st);
  EXPECT_TRUE(hasPostBox(groupStixels(st, cam, defaults()))) << "post behind the hedge";
}

TEST(stixelRoofPieces, KeysAreReadAndRangeChecked) {
  YAML::Node n;
  n["roof_piece_max_stixels"] = 0;
  n["roof_piece_max_gap_px"] = 4;
  n["roof_piece_top_tolerance_px"] = 3;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_EQ(p.roof_piece_max_stixels, 0);
  EXPECT_EQ(p.roof_piece_max_gap_px, 4);
  EXPECT_EQ(p.roof_piece_top_tolerance_px, 3);
  expectRejected("roof_piece_max_stixels", -1);
  expectRejected("roof_piece_max_stixels", 101);
  expectRejected("roof_piece_max_gap_px", -1);
  expectRejected("roof_piece_max_gap_px", 51);
  expectRejected("roof_piece_top_tolerance_px", -1);
  expectRejected("roof_piece_top_tolerance_px", 51);
  EXPECT_EQ(Params{}.roof_piece_max_stixels, 3);
}

}  // namespace
}  // namespace nerv::stixel

// Low structures along the road (low_runs.hpp): a guard rail receding from 8
// to 19 m gives no hypothesis (its stixels stay); a car's side seen alongside,
// a low wall facing the camera, a run with a tall part and a run of three
// strips keep theirs; the keys.
#include <gtest/gtest.h>

#include "hypothesis_grouping.hpp"
#include "low_runs.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// n strips from u0 to the left, receding from z0 by dz per strip, each height_m tall.
std::vector<Stixel> run(const StereoCamera& cam, int u0, int n, float z0, float dz, float height_m) {
  std::vector<Stixel> st;
  for (int k = n - 1; k >= 0; --k) st.push_back(stixelAt(cam, u0 - 5 * k, z0 + dz * k, height_m));
  return st;  // sorted by u
}

std::vector<const Stixel*> pointers(const std::vector<Stixel>& st) {
  std::vector<const Stixel*> g;
  for (const Stixel& s : st) g.push_back(&s);
  return g;
}

GroupingParams withLowRuns(bool on) {
  const Params d;
  GroupingParams p;
  p.low_runs.max_height_m = on ? d.low_run_max_height_m : 0.0f;
  p.low_runs.min_depth_span_m = d.low_run_min_depth_span_m;
  p.low_runs.min_stixels = d.low_run_min_stixels;
  return p;
}

TEST(stixelLowRuns, AGuardRailAlongTheRoadGivesNoHypothesis) {
  const StereoCamera cam = kittiLikeCamera();
  // highway seed 23 frame 4: the rail at the right edge, 0.75 m strips, 8 m to 19 m
  const std::vector<Stixel> rail = run(cam, 1200, 12, 8.0f, 1.0f, 0.75f);
  EXPECT_TRUE(isLowRun(pointers(rail), cam, withLowRuns(true).low_runs));
  EXPECT_EQ(groupStixels(rail, cam, withLowRuns(false)).size(), 1u) << "without the rule it is one box";
  EXPECT_TRUE(groupStixels(rail, cam, withLowRuns(true)).empty());
}

TEST(stixelLowRuns, ACarsSideAlongsideKeepsItsBox) {
  const StereoCamera cam = kittiLikeCamera();
  // a car in the next lane seen from its side: 1.45 m strips from 6 to 10.5 m
  const std::vector<Stixel> side = run(cam, 1200, 10, 6.0f, 0.5f, 1.45f);
  EXPECT_FALSE(isLowRun(pointers(side), cam, withLowRuns(true).low_runs));
  EXPECT_EQ(groupStixels(side, cam, withLowRuns(true)).size(), 1u);
}

TEST(stixelLowRuns, ALowWallFacingTheCameraKeepsItsBox) {
  const StereoCamera cam = kittiLikeCamera();
  const std::vector<Stixel> wall = run(cam, 700, 12, 15.0f, 0.0f, 0.8f);
  EXPECT_FALSE(isLowRun(pointers(wall), cam, withLowRuns(true).low_runs));
  EXPECT_EQ(groupStixels(wall, cam, withLowRuns(true)).size(), 1u);
}

TEST(stixelLowRuns, TheNinetiethPercentileDecides) {
  const StereoCamera cam = kittiLikeCamera();
  const LowRunParams p = withLowRuns(true).low_runs;
  std::vector<Stixel> rail = run(cam, 1200, 12, 8.0f, 1.0f, 0.75f);
  rail[5] = stixelAt(cam, rail[5].u, rail[5].depth_m, 1.6f);  // one post of the rail
  EXPECT_TRUE(isLowRun(pointers(rail), cam, p)) << "one tall strip in twelve";
  rail[6] = stixelAt(cam, rail[6].u, rail[6].depth_m, 1.6f);
  rail[7] = stixelAt(cam, rail[7].u, rail[7].depth_m, 1.6f);
  EXPECT_FALSE(isLowRun(pointers(rail), cam, p)) << "a quarter of the strips tall: something stands there";
}

TEST(stixelLowRuns, ShortOrShallowRunsAreNotRails) {
  const StereoCamera cam = kittiLikeCamera();
  const LowRunParams p = withLowRuns(true).low_runs;
  EXPECT_FALSE(isLowRun(pointers(run(cam, 1200, 3, 8.0f, 3.0f, 0.75f)), cam, p)) << "three strips";
  EXPECT_FALSE(isLowRun(pointers(run(cam, 1200, 8, 8.0f, 0.5f, 0.75f)), cam, p)) << "3.5 m of depth";
  EXPECT_FALSE(isLowRun({}, cam, p));
  EXPECT_FALSE(isLowRun(pointers(run(cam, 1200, 12, 8.0f, 1.0f, 0.75f)), cam, withLowRuns(false).low_runs))
      << "off";
}

TEST(stixelLowRuns, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"low_run_max_height_m", &Params::low_run_max_height_m},
                       {"low_run_min_depth_span_m", &Params::low_run_min_depth_span_m}},
                      {0.0, 8.0});
  expectRejected("low_run_max_height_m", 11.0);
  expectRejected("low_run_min_stixels", 0);
  const Params d;
  EXPECT_EQ(d.low_run_max_height_m, 1.0f);
  EXPECT_EQ(d.low_run_min_depth_span_m, 5.0f);
  EXPECT_EQ(d.low_run_min_stixels, 4);
}

}  // namespace
}  // namespace nerv::stixel

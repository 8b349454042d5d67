// Top search of the height segmentation (stixel_extraction.hpp): a thin
// upright body whose torso rows the matcher reads toward the background gets
// its full height when its head resumes the body's disparity above them; a
// surface just behind an object, at the near-miss disparity, does not extend
// the object's top, nor does a head beyond the extension limit; the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include "stixel_estimator.hpp"
#include "stixel_extraction.hpp"
#include "stixel_key_checks.hpp"

namespace nerv::stixel {
namespace {

// A level camera 1.65 m over a flat road, horizon at row 150, fx*B 388.8:
// ground disparity (v - 150) * 0.327. Each row below the horizon holds the
// road, rows above 171 a facade at 7 px (55 m); columns [20, 25) are the strip.
constexpr int kCols = 45, kRows = 240, kU0 = 20, kU1 = 25;
constexpr float kSlope = 0.327f, kHorizon = 150.0f;

GroundModel flatRoad() {
  GroundModel g;
  g.valid = true;
  g.vd_slope = kSlope;
  g.vd_intercept = -kSlope * kHorizon;
  g.horizon_row = kHorizon;
  g.height_m = 1.65f;
  return g;
}

cv::Mat roadAndFacade() {
  cv::Mat disp(kRows, kCols, CV_32F, cv::Scalar(0.0f));
  for (int v = 0; v < kRows; ++v) {
    const float road = kSlope * (static_cast<float>(v) - kHorizon);
    disp.row(v).setTo(road > 7.0f ? road : 7.0f);
  }
  return disp;
}

void fill(cv::Mat& disp, int v0, int v1, float d, int u0 = kU0, int u1 = kU1) {
  disp(cv::Rect(u0, v0, u1 - u0, v1 - v0 + 1)).setTo(d);
}

// The object of every case: d 10.5 px (37 m) standing on the road at row 182.
constexpr float kD = 10.5f;
constexpr int kFoot = 182;

int top(const cv::Mat& disp, const TopSearch& t) {
  return segmentTopRow(disp, flatRoad(), 0.2f, kU0, kU1, kFoot, 0, kD, t);
}

// The default band (1.5 px beyond the 1 px tolerance: 8.0-9.5 px are near misses).
TopSearch rule() {
  TopSearch t;
  t.tolerance_px = 1.0f;
  t.near_miss_px = Params{}.top_near_miss_px;
  t.max_extension_rows = 10;  // 0.5 m at 37 m
  t.min_resume_rows = 2;      // 0.1 m
  return t;
}

TEST(stixelTopSearch, AThinBodysTorsoReadTowardTheBackgroundKeepsItsHead) {
  cv::Mat disp = roadAndFacade();
  fill(disp, 150, kFoot, kD);    // a cyclist 1.7 m tall (33 rows), head rows 150-152
  fill(disp, 153, 158, 9.2f);    // torso read 1.3 px low: background bleeding into a thin body
  TopSearch off = rule();
  off.near_miss_px = 0.0f;
  EXPECT_EQ(top(disp, off), 159) << "plain segmentation stops below the torso";
  EXPECT_EQ(top(disp, rule()), 150) << "the head above the torso is the top";
}

TEST(stixelTopSearch, ASurfaceJustBehindTheObjectDoesNotRaiseItsTop) {
  cv::Mat disp = roadAndFacade();
  fill(disp, 160, kFoot, kD);    // a car's rear, roof at row 160
  fill(disp, 150, 159, 9.3f);    // a car 4 m behind it, 1.2 px farther: a near miss
  // Stray matches above it (2 of 5 columns, never most of a row).
  fill(disp, 150, 152, kD, kU0, kU0 + 2);
  EXPECT_EQ(top(disp, rule()), 160);
}

TEST(stixelTopSearch, AHeadBeyondTheExtensionLimitIsNotJoined) {
  cv::Mat disp = roadAndFacade();
  fill(disp, 140, kFoot, kD);
  fill(disp, 144, 158, 9.2f);    // 15 rows of near misses: more than a torso
  const int plain = 159;
  TopSearch off = rule();
  off.near_miss_px = 0.0f;
  EXPECT_EQ(top(disp, off), plain);
  // The rows it could reach (149..158) are all near misses: no object resumes.
  EXPECT_EQ(top(disp, rule()), plain);
  TopSearch wide = rule();
  wide.max_extension_rows = 25;
  EXPECT_EQ(top(disp, wide), 140);
}

TEST(stixelTopSearch, BackgroundFartherThanTheNearMissBandStillEndsTheTop) {
  cv::Mat disp = roadAndFacade();
  fill(disp, 150, kFoot, kD);
  fill(disp, 153, 158, 7.5f);    // 3 px low: a facade at 52 m, not a biased torso
  EXPECT_EQ(top(disp, rule()), 159);
}

TEST(stixelTopSearch, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"top_near_miss_px", &Params::top_near_miss_px},
                       {"top_max_extension_m", &Params::top_max_extension_m},
                       {"top_min_resume_m", &Params::top_min_resume_m}},
                      {0.5, 0.3, 0.2});
  expectRejected("top_near_miss_px", 11.0);
  expectRejected("top_max_extension_m", 6.0);
  expectRejected("top_min_resume_m", 6.0);
  EXPECT_GT(Params{}.top_near_miss_px, 0.0f) << "on by default";
}

}  // namespace
}  // namespace nerv::stixel

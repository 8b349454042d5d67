// Free or unseen (observed_free_space.hpp): each free-space strip's share of
// measured pixels between the image's lower edge and its free-space boundary.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>

#include "dataset.hpp"
#include "observed_free_space.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

int strips(const StereoCamera& cam) { return (cam.width + 4) / 5; }

TEST(stixelObservedFreeSpace, AClearRoadIsObservedEverywhere) {
  const StereoCamera cam = kittiLikeCamera();
  const StixelResult r = estimateStixels(renderDisparity(RoadScene{}, cam), cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  ASSERT_EQ(static_cast<int>(r.observed.observed.size()), strips(cam));
  EXPECT_EQ(r.observed.column_width_px, 5);
  EXPECT_FLOAT_EQ(r.observed.min_observed, 0.3f);
  for (size_t k = 0; k < r.observed.observed.size(); ++k) EXPECT_FLOAT_EQ(r.observed.observed[k], 1.0f) << k;
  EXPECT_EQ(r.observed.num_unobserved, 0);
  EXPECT_FLOAT_EQ(r.observed.observed_share, 1.0f);
}

TEST(stixelObservedFreeSpace, ABlindedRegionIsUnknownNotFree) {
  // A smudge over columns [100, 400): no disparity, so no obstacle evidence and
  // no boundary there - free by the boundary search, unobserved here.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.boxes.push_back({15.0f, 2.0f, 4.0f, 1.5f});  // a car on the right, seen
  cv::Mat disp = renderDisparity(scene, cam);
  disp.colRange(100, 400).setTo(0.0f);
  const StixelResult r = estimateStixels(disp, cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  ASSERT_EQ(static_cast<int>(r.observed.observed.size()), strips(cam));
  for (int k = 0; k < strips(cam); ++k) {
    const bool blind = k * 5 >= 100 && k * 5 < 400;
    if (blind) EXPECT_FLOAT_EQ(r.observed.observed[k], 0.0f) << k;
    else EXPECT_FLOAT_EQ(r.observed.observed[k], 1.0f) << k;
  }
  EXPECT_EQ(r.observed.num_unobserved, 60);
  EXPECT_TRUE(r.observed.observed_share > 0.5f && r.observed.observed_share < 0.9f) << r.observed.observed_share;
  // The car is found; nothing is proposed in the smudge.
  ASSERT_EQ(r.hypotheses.size(), 1u);
  EXPECT_GT(r.hypotheses[0].box.x, 400);
}

TEST(stixelObservedFreeSpace, OnlyTheRowsBelowTheBoundaryCount) {
  // By hand: a ground line, a strip whose nearest obstacle is at 20 px of
  // disparity, and holes placed above and below the row where the road reaches it.
  const StereoCamera cam = kittiLikeCamera();
  const StixelResult r = estimateStixels(renderDisparity(RoadScene{}, cam), cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  const GroundModel& g = r.ground;
  cv::Mat disp(cam.height, cam.width, CV_32F, cv::Scalar(10.0f));
  std::vector<int> boundary(strips(cam), -1);
  boundary[50] = 20;
  const int v0 = static_cast<int>(std::ceil((20.0 - g.vd_intercept) / g.vd_slope));
  ASSERT_GT(v0, 0);
  ASSERT_LT(v0 + 10, cam.height);
  disp(cv::Rect(250, 0, 5, v0)).setTo(0.0f);                     // above its free space: not counted
  disp(cv::Rect(250, cam.height - 10, 5, 10)).setTo(0.0f);       // its lowest 10 rows
  disp.at<float>(cam.height - 1, 255) = std::nanf("");            // strip 51: one NaN pixel
  ObservedParams p;
  const ObservedFreeSpace o = observeFreeSpace(disp, cam, g, boundary, p);
  EXPECT_FLOAT_EQ(o.observed[50], static_cast<float>(cam.height - v0 - 10) / (cam.height - v0));
  // Strip 51 is free up to 60 m: its rows from where the road is 60 m away.
  const int v60 = static_cast<int>(std::ceil((cam.disparityFromDepth(60.0) - g.vd_intercept) / g.vd_slope));
  EXPECT_FLOAT_EQ(o.observed[51], 1.0f - 1.0f / (5.0f * (cam.height - v60)));
  EXPECT_FLOAT_EQ(o.observed[49], 1.0f);
  // An obstacle whose foot lies below the image leaves no free space: observed.
  boundary[10] = 1000;
  disp.colRange(50, 55).setTo(0.0f);
  EXPECT_FLOAT_EQ(observeFreeSpace(disp, cam, g, boundary, p).observed[10], 1.0f);
  // The threshold.
  p.min_observed = 0.99f;
  EXPECT_EQ(observeFreeSpace(disp, cam, g, boundary, p).num_unobserved, 1);  // strip 50 alone
}

TEST(stixelObservedFreeSpace, WithoutGroundNothingIsFree) {
  const StereoCamera cam = kittiLikeCamera();
  const cv::Mat invalid(cam.height, cam.width, CV_32F, cv::Scalar(0.0f));
  const StixelResult r = estimateStixels(invalid, cam, Params{});
  EXPECT_FALSE(r.ground.valid);
  ASSERT_EQ(static_cast<int>(r.observed.observed.size()), strips(cam));
  EXPECT_EQ(r.observed.num_unobserved, strips(cam));
  EXPECT_FLOAT_EQ(r.observed.observed_share, 0.0f);
  // No disparity at all: no strips.
  EXPECT_TRUE(estimateStixels(cv::Mat(), cam, Params{}).observed.observed.empty());
}

TEST(stixelObservedFreeSpace, ARealFrameBlindedByGlareOrADropIsUnknownNotFree) {
  // KITTI 0926 frame 5 through the real matcher: as recorded, then with glare (the
  // lower left quarter saturated) on the left lens or on both, a water drop (a
  // strong blur) or a black cover on the left lens.
  const std::string dir = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no " << dir;
  const Dataset ds = openDataset(dir);
  ASSERT_GT(ds.frames.size(), 5u);
  const DatasetFrame& f = ds.frames[5];
  const cv::Mat left = cv::imread(f.left_path, cv::IMREAD_GRAYSCALE), right = cv::imread(f.right_path, cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(left.empty());
  const auto matcher = stereo::StereoMatcher::create(stereo::Params{});
  const Params p;
  auto run = [&](const cv::Mat& l, const cv::Mat& r) {
    cv::Mat d;
    matcher->compute(l, r, d);
    const StixelResult st = estimateStixels(d, f.camera, p);
    EXPECT_TRUE(st.ground.valid);
    int left_half = 0;  // strips over columns 0-599
    for (int k = 0; k < 120; ++k) left_half += st.observed.observed[k] < st.observed.min_observed ? 1 : 0;
    return std::make_pair(st.observed.num_unobserved, left_half);
  };
  const auto clear = run(left, right);
  EXPECT_LE(clear.first, 12);  // the image borders (docs/stixel.md "Free or unseen")
  cv::Mat glare = left.clone();
  glare(cv::Rect(0, 150, 600, 225)).setTo(255);
  cv::Mat right_glare = right.clone();
  right_glare(cv::Rect(0, 150, 600, 225)).setTo(255);
  cv::Mat drop = left.clone();
  cv::GaussianBlur(drop(cv::Rect(0, 100, 600, 275)), drop(cv::Rect(0, 100, 600, 275)), cv::Size(0, 0), 12);
  cv::Mat covered = left.clone();  // dirt or a wiper: black
  covered(cv::Rect(0, 150, 600, 225)).setTo(0);
  // The same glare in both lenses matches itself as far away unless saturated
  // patches are left unmeasured (stereo_matcher.flat_census_invalid, the default).
  for (const auto& [l, r] : {std::make_pair(glare, right), std::make_pair(glare, right_glare), std::make_pair(drop, right),
                             std::make_pair(covered, right)}) {
    const auto [all, left_half] = run(l, r);
    EXPECT_GE(left_half, 110);  // of 120
    // more than the stixel service's max_unobserved_fraction (0.4): an "unobserved" error
    EXPECT_GT(all, 0.4 * 249);
  }
}

TEST(stixelObservedFreeSpace, ItsKeyIsRead) {
  expectFloatKeysRead({{"min_observed_share", &Params::min_observed_share}}, {0.5});
  expectRejected("min_observed_share", 1.5);
}

}  // namespace
}  // namespace nerv::stixel

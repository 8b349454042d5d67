// Is the rig still rectified (services/stereo_matcher/rectification_check.hpp)?
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <random>

#include "rectification_check.hpp"
#include "stereo_matcher.hpp"

namespace nerv::stereo {
namespace {

// Smooth random texture (blurred noise), as a camera sees a textured wall.
cv::Mat texture(int width, int height, unsigned seed) {
  cv::Mat noise(height, width, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(0, 0), 1.5);
  cv::normalize(smooth, smooth, 0, 255, cv::NORM_MINMAX);
  return smooth;
}

// The right view of a fronto-parallel wall at disparity d, its rows moved by dy:
// the left view's (x, y) appears at (x - d, y + dy).
cv::Mat rightView(const cv::Mat& left, double d, double dy) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -d, 0, 1, dy);
  cv::Mat right;
  cv::warpAffine(left, right, shift, left.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return right;
}

TEST(stereoRowOffset, MeasuresTheRowsOfAKnownShift) {
  const cv::Mat left = texture(640, 240, 7);
  const cv::Mat disparity(left.size(), CV_32FC1, cv::Scalar(20.0f));
  for (const double dy : {-2.0, -0.5, 0.0, 0.3, 1.5, 4.0}) {
    const RowOffset m = measureRowOffset(left, rightView(left, 20, dy), disparity);
    ASSERT_TRUE(m.valid) << dy;
    EXPECT_NEAR(m.offset_px, dy, 0.05) << dy;
    EXPECT_LT(m.spread_px, 0.1) << dy;
    EXPECT_GE(m.points, 100) << dy;
  }
}

TEST(stereoRowOffset, PointsOffTheirDisparityAreLeftOut) {
  // Half the disparity map is wrong by 5 px (a matcher's error): those tracks land
  // 5 px from where the disparity says and do not vote; the offset stays right.
  const cv::Mat left = texture(640, 240, 11);
  cv::Mat disparity(left.size(), CV_32FC1, cv::Scalar(20.0f));
  disparity(cv::Rect(0, 0, 320, 240)).setTo(25.0f);
  const RowOffset m = measureRowOffset(left, rightView(left, 20, 0.8), disparity);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(m.offset_px, 0.8, 0.05);
  EXPECT_LT(m.points, 150);  // about half the 200 tracked points
}

TEST(stereoRowOffset, NoTextureNoDisparityOrBadInputGiveNoMeasurement) {
  const cv::Mat left = texture(640, 240, 3);
  const cv::Mat right = rightView(left, 20, 1);
  const cv::Mat disparity(left.size(), CV_32FC1, cv::Scalar(20.0f));
  const cv::Mat flat(left.size(), CV_8UC1, cv::Scalar(128));
  EXPECT_FALSE(measureRowOffset(flat, flat, disparity).valid);
  EXPECT_FALSE(measureRowOffset(left, right, cv::Mat::zeros(left.size(), CV_32FC1)).valid);
  cv::Mat nan_disparity(left.size(), CV_32FC1, cv::Scalar(NAN));
  EXPECT_FALSE(measureRowOffset(left, right, nan_disparity).valid);
  EXPECT_FALSE(measureRowOffset(left, right, cv::Mat()).valid);
  EXPECT_FALSE(measureRowOffset(left, right(cv::Rect(0, 0, 320, 240)).clone(), disparity).valid);
  cv::Mat colour;
  cv::cvtColor(left, colour, cv::COLOR_GRAY2BGR);
  EXPECT_FALSE(measureRowOffset(colour, right, disparity).valid);
  EXPECT_FALSE(measureRowOffset(left(cv::Rect(0, 0, 8, 8)).clone(), right(cv::Rect(0, 0, 8, 8)).clone(),
                                disparity(cv::Rect(0, 0, 8, 8)).clone())
                   .valid);
}

TEST(stereoRowOffset, MonitorGivesAVerdictEveryWindowOnTheMedian) {
  RowOffsetMonitor monitor(4, 0.4f);
  const auto at = [](float offset, int points = 150) { return RowOffset{true, points, offset, 0.1f}; };
  EXPECT_FALSE(monitor.add(at(0.1f)));
  EXPECT_FALSE(monitor.add(RowOffset{}));  // no measurement: ignored
  EXPECT_FALSE(monitor.add(at(0.9f)));     // one bad frame
  EXPECT_FALSE(monitor.add(at(0.0f)));
  EXPECT_TRUE(monitor.add(at(0.2f, 120)));  // the fourth valid one: a verdict
  EXPECT_NEAR(monitor.median(), 0.15f, 1e-6);
  EXPECT_FALSE(monitor.misaligned());
  EXPECT_EQ(monitor.describe(),
            "the right view's rows lie 0.15 px below the left's (median of the last 4 checks, 120-150 points each)");
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(monitor.add(at(-1.0f)));
  EXPECT_TRUE(monitor.add(at(-1.2f)));
  EXPECT_TRUE(monitor.misaligned());
  EXPECT_NEAR(monitor.median(), -1.0f, 1e-6);
  EXPECT_NE(monitor.describe().find("1.00 px above"), std::string::npos) << monitor.describe();
}

// The real KITTI frames: as recorded within 0.1 px; the right view moved by a row
// (a knocked rig), measured within 0.1 px on the matcher's own disparity.
TEST(stereoRowOffset, KittiFramesAsRecordedAndMoved) {
  const std::filesystem::path dir = std::filesystem::path(NERV_SHARED_DATA) / "kitti_raw_0926_seq";
  if (!std::filesystem::exists(dir / "left/0000000000.png")) GTEST_SKIP() << "../shared/data is absent";
  const cv::Mat left = cv::imread((dir / "left/0000000000.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat right = cv::imread((dir / "right/0000000000.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(left.empty() || right.empty());
  auto matcher = StereoMatcher::create(Params{});
  for (const double dy : {0.0, 1.0, -1.5}) {
    cv::Mat moved = right.clone(), disparity;
    if (dy != 0) moved = rightView(right, 0, dy);
    matcher->compute(left, moved, disparity);
    const RowOffset m = measureRowOffset(left, moved, disparity);
    ASSERT_TRUE(m.valid) << dy;
    EXPECT_NEAR(m.offset_px, dy, 0.1) << dy;
    EXPECT_GE(m.points, 100) << dy;
  }
}

}  // namespace
}  // namespace nerv::stereo

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
    EXPECT_NEAR(m.worst_px, std::abs(dy), 0.08) << dy;  // a shift: the same everywhere
    EXPECT_NEAR(m.slope_x, 0, 2e-4) << dy;
    EXPECT_NEAR(m.slope_y, 0, 2e-4) << dy;
    EXPECT_LT(m.spread_px, 0.1) << dy;
    EXPECT_GE(m.points, 100) << dy;
  }
}

TEST(stereoRowOffset, ARightCameraTurnedAboutItsAxisTurnsTheRows) {
  // Turned by 0.2 deg about the view's centre: rows 1 px off at the sides, about 0 in
  // the middle, so the median alone would pass it; the plane's slope is the turn.
  const cv::Mat left = texture(640, 240, 5);
  const cv::Mat disparity(left.size(), CV_32FC1, cv::Scalar(20.0f));
  const double th = 0.2 * CV_PI / 180, c = std::cos(th), sn = std::sin(th), cx = 320, cy = 120;
  // (x, y) -> turned about (cx, cy), then 20 px to the left.
  const cv::Mat turn = (cv::Mat_<double>(2, 3) << c, -sn, cx - c * cx + sn * cy - 20, sn, c, cy - sn * cx - c * cy);
  cv::Mat right;
  cv::warpAffine(left, right, turn, left.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  const RowOffset m = measureRowOffset(left, right, disparity);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(m.slope_x, std::tan(th), 0.03 * std::tan(th));
  EXPECT_NEAR(m.offset_px, 0, 0.05);
  EXPECT_NEAR(m.slope_y, 0, 2e-4);
  // The 90th percentile of |u| over points spread across 600 columns: about 270 px.
  EXPECT_GT(m.worst_px, 0.8);
  EXPECT_LT(m.worst_px, 1.1);
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
  const auto at = [](float offset, int points = 150) {
    RowOffset r;
    r.valid = true, r.points = points, r.offset_px = offset, r.worst_px = std::abs(offset), r.spread_px = 0.1f;
    return r;
  };
  EXPECT_FALSE(monitor.add(at(0.1f)));
  EXPECT_FALSE(monitor.add(RowOffset{}));  // no measurement: ignored
  EXPECT_FALSE(monitor.add(at(0.9f)));     // one bad frame
  EXPECT_FALSE(monitor.add(at(0.0f)));
  EXPECT_TRUE(monitor.add(at(0.2f, 120)));  // the fourth valid one: a verdict
  EXPECT_NEAR(monitor.median().offset_px, 0.15f, 1e-6);
  EXPECT_FALSE(monitor.misaligned());
  EXPECT_EQ(monitor.describe(),
            "the right view's rows lie 0.15 px below the left's at its centre and up to 0.15 px off where it "
            "matches (turned 0.00 deg; median of the last 4 checks, 120-150 points each)");
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(monitor.add(at(-1.0f)));
  EXPECT_TRUE(monitor.add(at(-1.2f)));
  EXPECT_TRUE(monitor.misaligned());
  EXPECT_NEAR(monitor.median().offset_px, -1.0f, 1e-6);
  EXPECT_NE(monitor.describe().find("1.00 px above"), std::string::npos) << monitor.describe();
  // A turn: the rows' median near 0, but 0.8 px off where the view matches.
  RowOffsetMonitor turned(2, 0.4f);
  RowOffset t = at(0.05f);
  t.slope_x = 0.0017f, t.worst_px = 0.8f;
  EXPECT_FALSE(turned.add(t));
  EXPECT_TRUE(turned.add(t));
  EXPECT_TRUE(turned.misaligned());
  EXPECT_NE(turned.describe().find("up to 0.80 px off where it matches (turned 0.10 deg"), std::string::npos)
      << turned.describe();
}

// The real KITTI frames: as recorded within 0.2 px everywhere; the right view moved by
// +1 and -1.5 rows (a knocked rig), measured within 0.2 px on the matcher's own disparity.
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
    EXPECT_NEAR(m.offset_px, dy, 0.2) << dy;
    EXPECT_NEAR(m.worst_px, std::abs(dy), 0.2) << dy;
    EXPECT_GE(m.points, 100) << dy;
  }
}

}  // namespace
}  // namespace nerv::stereo

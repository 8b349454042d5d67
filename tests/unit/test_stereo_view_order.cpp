// Are the two views the right way round (view_order_check.hpp), and the textured points
// both checks follow (textured_points.hpp)?
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>

#include "stereo_scene_texture.hpp"
#include "textured_points.hpp"
#include "view_order_check.hpp"

namespace nerv::stereo {
namespace {

cv::Mat texture(int width, int height, unsigned seed) { return multiScaleTexture(width, height, seed); }

// The right view of a wall at disparity d: the left view's (x, y) at (x - d, y).
cv::Mat rightView(const cv::Mat& left, double d) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -d, 0, 1, 0);
  cv::Mat right;
  cv::warpAffine(left, right, shift, left.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return right;
}

TEST(stereoTexturedPoints, OnlyWhereTheImageChangesBothWays) {
  // Vertical stripes change along rows only: no point. A bright square: its corners.
  cv::Mat stripes(120, 160, CV_8UC1);
  for (int x = 0; x < stripes.cols; ++x) stripes.col(x).setTo((x / 4) % 2 ? 200 : 50);
  EXPECT_TRUE(texturedPoints(stripes, {4, 7, 100}).empty());
  cv::Mat square = cv::Mat::zeros(120, 160, CV_8UC1);
  square(cv::Rect(40, 30, 80, 60)).setTo(255);
  const std::vector<cv::Point2f> corners = texturedPoints(square, {2, 7, 4});
  ASSERT_EQ(corners.size(), 4u);
  for (const cv::Point2f& c : corners) {
    const bool near_corner = (std::abs(c.x - 40) <= 4 || std::abs(c.x - 120) <= 4) &&
                             (std::abs(c.y - 30) <= 4 || std::abs(c.y - 90) <= 4);
    EXPECT_TRUE(near_corner) << c;
  }
  // The filter and the limits: nothing accepted, nothing returned; the best max_points otherwise.
  const cv::Mat tex = texture(160, 120, 1);
  EXPECT_TRUE(texturedPoints(tex, {8, 7, 50}, [](int, int) { return false; }).empty());
  EXPECT_EQ(texturedPoints(tex, {8, 7, 50}).size(), 50u);
  for (const cv::Point2f& c : texturedPoints(tex, {8, 7, 50}, [](int x, int) { return x < 80; }))
    EXPECT_LT(c.x, 80);
  EXPECT_TRUE(texturedPoints(cv::Mat(), {8, 7, 50}).empty());
  EXPECT_TRUE(texturedPoints(tex(cv::Rect(0, 0, 10, 10)).clone(), {8, 7, 50}).empty());
  cv::Mat colour;
  cv::cvtColor(tex, colour, cv::COLOR_GRAY2BGR);
  EXPECT_TRUE(texturedPoints(colour, {8, 7, 50}).empty());
}

TEST(stereoViewOrder, ARigTheRightWayRoundAndSwapped) {
  const cv::Mat left = texture(640, 240, 9);
  for (const double d : {3.0, 20.0, 40.0}) {  // the pyramid reaches about 50 px sideways
    const cv::Mat right = rightView(left, d);
    const ViewOrder ok = measureViewOrder(left, right);
    ASSERT_TRUE(ok.valid) << d;
    EXPECT_FALSE(ok.swapped) << d;
    EXPECT_LT(ok.share_rightward, 0.05) << d;
    EXPECT_GE(ok.votes, 100) << d;
    const ViewOrder swapped = measureViewOrder(right, left);
    ASSERT_TRUE(swapped.valid) << d;
    EXPECT_TRUE(swapped.swapped) << d;
    EXPECT_GT(swapped.share_rightward, 0.95) << d;
  }
}

TEST(stereoViewOrder, NothingToFollowGivesNoVerdict) {
  const cv::Mat flat(240, 640, CV_8UC1, cv::Scalar(90));
  EXPECT_FALSE(measureViewOrder(flat, flat).valid);
  // A wall at infinity (no sideways motion) says nothing about the order.
  const cv::Mat left = texture(640, 240, 4);
  const ViewOrder far = measureViewOrder(left, left);
  EXPECT_FALSE(far.valid);
  EXPECT_FALSE(far.swapped);
  EXPECT_FALSE(measureViewOrder(left, left(cv::Rect(0, 0, 320, 240)).clone()).valid);
  EXPECT_FALSE(measureViewOrder(cv::Mat(), cv::Mat()).valid);
}

TEST(stereoViewOrder, KittiFramesAsRecordedAndSwapped) {
  const std::filesystem::path dir = std::filesystem::path(NERV_SHARED_DATA) / "kitti_raw_0926_seq";
  if (!std::filesystem::exists(dir / "left/0000000000.png")) GTEST_SKIP() << "../shared/data is absent";
  for (const char* frame : {"0000000000", "0000000005", "0000000010"}) {
    const cv::Mat left = cv::imread((dir / "left" / (std::string(frame) + ".png")).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat right = cv::imread((dir / "right" / (std::string(frame) + ".png")).string(), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(left.empty() || right.empty()) << frame;
    const ViewOrder ok = measureViewOrder(left, right), swapped = measureViewOrder(right, left);
    ASSERT_TRUE(ok.valid && swapped.valid) << frame;
    EXPECT_FALSE(ok.swapped) << frame << " " << ok.share_rightward;
    EXPECT_TRUE(swapped.swapped) << frame << " " << swapped.share_rightward;
  }
}

}  // namespace
}  // namespace nerv::stereo

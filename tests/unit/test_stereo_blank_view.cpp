// Does one view show nothing (services/stereo_matcher/blank_view.hpp)?
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>

#include "blank_view.hpp"

namespace nerv::stereo {
namespace {

cv::Mat texture(int width, int height, unsigned seed) {
  cv::Mat noise(height, width, CV_8UC1);
  cv::RNG(seed).fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(0, 0), 2.0);
  cv::normalize(smooth, smooth, 0, 255, cv::NORM_MINMAX);
  return smooth;
}

// A covered lens: a flat gray with sensor noise of `sigma` gray levels.
cv::Mat covered(int width, int height, double level, double sigma) {
  cv::Mat m(height, width, CV_8UC1);
  cv::randn(m, level, sigma);
  return m;
}

TEST(stereoBlankView, TheViewWithoutTextureIsNamed) {
  const cv::Mat scene = texture(640, 240, 3);
  const ViewTexture both = compareViewTexture(scene, texture(640, 240, 4));
  EXPECT_EQ(both.blank, "");
  EXPECT_EQ(both.left, 300);  // counting stops at max_points
  EXPECT_EQ(both.right, 300);
  for (const double level : {4.0, 90.0, 250.0}) {  // a cap, a gray cover, a saturated sensor
    const ViewTexture r = compareViewTexture(scene, covered(640, 240, level, 3.0));
    EXPECT_EQ(r.blank, "right") << level;
    EXPECT_EQ(r.right, 0) << level;
    EXPECT_EQ(compareViewTexture(covered(640, 240, level, 3.0), scene).blank, "left") << level;
  }
  cv::Mat fogged;
  cv::GaussianBlur(scene, fogged, cv::Size(0, 0), 8);
  EXPECT_EQ(compareViewTexture(scene, fogged).blank, "right");
}

TEST(stereoBlankView, BothDarkOrMismatchedIsNoVerdict) {
  // Night, fog over both: neither view has texture; no camera to blame.
  EXPECT_EQ(compareViewTexture(covered(640, 240, 10, 2), covered(640, 240, 12, 2)).blank, "");
  // Too little texture in the good view to compare against (min_textured 50).
  cv::Mat sparse = covered(640, 240, 90, 1);
  cv::rectangle(sparse, cv::Rect(100, 100, 20, 20), cv::Scalar(250), cv::FILLED);
  EXPECT_EQ(compareViewTexture(sparse, covered(640, 240, 90, 1)).blank, "");
  const cv::Mat scene = texture(640, 240, 5);
  EXPECT_EQ(compareViewTexture(scene, cv::Mat()).blank, "");
  EXPECT_EQ(compareViewTexture(scene, scene(cv::Rect(0, 0, 320, 240)).clone()).blank, "");
}

TEST(stereoBlankView, KittiViewsAndACoveredOne) {
  const std::filesystem::path dir = std::filesystem::path(NERV_SHARED_DATA) / "kitti_raw_0926_seq";
  if (!std::filesystem::exists(dir / "left/0000000000.png")) GTEST_SKIP() << "../shared/data is absent";
  const cv::Mat left = cv::imread((dir / "left/0000000000.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat right = cv::imread((dir / "right/0000000000.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(left.empty() || right.empty());
  EXPECT_EQ(compareViewTexture(left, right).blank, "");
  cv::Mat fogged;
  cv::GaussianBlur(right, fogged, cv::Size(0, 0), 8);
  EXPECT_EQ(compareViewTexture(left, fogged).blank, "right");
  EXPECT_EQ(compareViewTexture(covered(left.cols, left.rows, 30, 3), right).blank, "left");
}

}  // namespace
}  // namespace nerv::stereo

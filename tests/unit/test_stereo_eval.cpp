// D1 / bad-2.0 scoring and the KITTI devkit background interpolation against
// hand-computed cases.
#include <gtest/gtest.h>

#include "disparity_metrics.hpp"

using namespace nerv::stereo;

namespace {
cv::Mat row(std::initializer_list<float> v) { return cv::Mat(std::vector<float>(v), true).reshape(1, 1); }
}  // namespace

TEST(stereoEval, BackgroundInterpolationPerRow) {
  // interior run: min of its neighbours; borders: nearest valid value
  cv::Mat d = row({0, 5, 0, 0, 3, 0, 8, 0});
  interpolateBackground(d);
  const cv::Mat expected = row({5, 5, 3, 3, 3, 3, 8, 8});
  EXPECT_EQ(cv::countNonZero(d != expected), 0) << d;
}

TEST(stereoEval, BackgroundInterpolationFillsEmptyRowsFromColumns) {
  cv::Mat d = (cv::Mat_<float>(4, 3) << 0, 0, 0,
                                        2, 0, 6,
                                        0, 0, 0,
                                        1, 0, 0);
  interpolateBackground(d);
  const cv::Mat expected = (cv::Mat_<float>(4, 3) << 2, 2, 6,
                                                     2, 2, 6,
                                                     0, 0, 0,
                                                     1, 1, 1);
  // rows 1 and 3 fill first ({2,2,6}, {1,1,1}), then columns extrapolate up and
  // down only (as the devkit): the empty row between valid rows stays invalid
  EXPECT_EQ(cv::countNonZero(d != expected), 0) << d;
}

TEST(stereoEval, D1NeedsBothThreeBixelsAndFivePercent) {
  const cv::Mat gt = row({100, 100, 10, 10, 50, 0});
  //                estimate:  104 ok (4 % < 5 %), 106 bad, 13 ok (3 px), 13.5 bad, invalid, no gt
  const cv::Mat est = row({104, 106, 13, 13.5, 0, 7});
  const DisparityScore s = scoreD1(est, gt);
  EXPECT_EQ(s.pixels, 5);
  // the invalid pixel takes min(13.5, 7) = 7 from its neighbours: |7 - 50| is bad
  EXPECT_DOUBLE_EQ(s.error_rate, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.density, 4.0 / 5.0);
}

TEST(stereoEval, BadTwoPixelsForMiddlebury) {
  const cv::Mat gt = row({20, 20, 20, 0, 40});
  const cv::Mat est = row({22, 22.5, 0, 9, 41});
  const DisparityScore s = scoreBad(est, gt, 2.0);
  EXPECT_EQ(s.pixels, 4);
  // 22 ok, 22.5 bad, invalid -> min(22.5, 9) = 9 bad, 41 ok
  EXPECT_DOUBLE_EQ(s.error_rate, 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(s.density, 3.0 / 4.0);
}

TEST(stereoEval, SubpixelErrorOverTheEstimatesOwnInliers) {
  const cv::Mat gt = row({10, 10, 10, 10, 10, 0});
  //                estimate: +0.25, -0.5, +1.0 (still an inlier), +1.5 (outlier), invalid, no gt
  const cv::Mat est = row({10.25, 9.5, 11, 11.5, 0, 12});
  const DisparityScore s = scoreBad(est, gt, 2.0);
  EXPECT_EQ(s.inliers, 3);  // the invalid pixel, filled by interpolation, is not one
  EXPECT_NEAR(s.inlier_mean_error, (0.25 + 0.5 + 1.0) / 3.0, 1e-6);
  EXPECT_NEAR(s.inlier_mean_bias, (0.25 - 0.5 + 1.0) / 3.0, 1e-6);  // signed: an offset shows
  const DisparityScore none = scoreD1(cv::Mat::zeros(1, 6, CV_32F), gt);
  EXPECT_EQ(none.inliers, 0);
  EXPECT_DOUBLE_EQ(none.inlier_mean_error, 0.0);
  EXPECT_DOUBLE_EQ(none.inlier_mean_bias, 0.0);
}

TEST(stereoEval, EmptyEstimateIsAllWrong) {
  const cv::Mat gt = row({5, 6, 7});
  const DisparityScore s = scoreD1(cv::Mat::zeros(1, 3, CV_32F), gt);
  EXPECT_DOUBLE_EQ(s.error_rate, 1.0);
  EXPECT_DOUBLE_EQ(s.density, 0.0);
}

TEST(stereoEval, KittiFrameIfPresent) {
  const std::string dir = std::string(NERV_SHARED_DATA) + "/kitti2015_000005";
  const auto frames = findEvalFrames(dir);
  if (frames.empty()) GTEST_SKIP() << dir << " not present";
  std::string kind;
  const cv::Mat gt = loadGroundTruth(frames[0].gt_path, kind);
  EXPECT_EQ(kind, "kitti");
  EXPECT_EQ(gt.size(), cv::Size(1242, 375));
  double hi;
  cv::minMaxLoc(gt, nullptr, &hi);
  EXPECT_GT(hi, 20.0);
  EXPECT_LT(hi, 256.0);
  EXPECT_DOUBLE_EQ(scoreD1(gt, gt).error_rate, 0.0);
}

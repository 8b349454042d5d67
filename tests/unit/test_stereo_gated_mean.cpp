// The depth-gated mean (gated_mean.hpp) against a plain reference and constructed maps.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <opencv2/core.hpp>

#include "gated_mean.hpp"
#include "stereo_matcher.hpp"

using namespace nerv::stereo;

namespace {

// The rule written out: the mean of the valid window values within the gate.
cv::Mat referenceGatedMean(const cv::Mat& d, const GatedMeanParams& p) {
  cv::Mat out = d.clone();
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) {
      const float c = d.at<float>(y, x);
      if (!(c > 0)) continue;
      const float gate = std::max(p.range_px, p.range_rel * c);
      double sum = 0;
      int n = 0;
      for (int yy = y - p.radius; yy <= y + p.radius; ++yy)
        for (int xx = x - p.radius; xx <= x + p.radius; ++xx) {
          if (yy < 0 || yy >= d.rows || xx < 0 || xx >= d.cols) continue;
          const float q = d.at<float>(yy, xx);
          if (q > 0 && std::fabs(q - c) <= gate) {
            sum += q;
            ++n;
          }
        }
      out.at<float>(y, x) = static_cast<float>(sum / n);
    }
  return out;
}

cv::Mat run(const cv::Mat& d, const GatedMeanParams& p, int row_begin = 0, int row_end = -1) {
  cv::Mat out = d.clone();
  gatedMeanRows(d, out, p, row_begin, row_end < 0 ? d.rows : row_end);
  return out;
}

}  // namespace

TEST(stereoGatedMean, MatchesThePlainReferenceOnRandomMapsWithHoles) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(1.0f, 60.0f), noise(-0.6f, 0.6f);
  for (const cv::Size size : {cv::Size(37, 11), cv::Size(64, 20), cv::Size(3, 5), cv::Size(9, 1)}) {
    cv::Mat d(size, CV_32F);
    for (int y = 0; y < d.rows; ++y)
      for (int x = 0; x < d.cols; ++x) {
        // blocks of similar disparity with scatter, and holes
        const float base = 5.0f + 10.0f * ((x / 7 + y / 5) % 3);
        d.at<float>(y, x) = rng() % 5 == 0 ? 0.0f : base + noise(rng) + (rng() % 9 == 0 ? value(rng) : 0.0f);
      }
    for (const GatedMeanParams p : {GatedMeanParams{2, 0.5f, 0.05f}, GatedMeanParams{1, 1.0f, 0.0f},
                                    GatedMeanParams{3, 0.3f, 0.1f}}) {
      const cv::Mat a = run(d, p), b = referenceGatedMean(d, p);
      for (int y = 0; y < d.rows; ++y)
        for (int x = 0; x < d.cols; ++x)
          ASSERT_NEAR(a.at<float>(y, x), b.at<float>(y, x), 1e-4f) << size << " at " << x << "," << y;
    }
  }
}

// The vector loop (8 or 4 pixels a step) and the per-pixel one at the row's ends give the same
// floats, not only close ones: the map shifted right by s invalid columns puts each pixel in
// the other loop or another lane, and nothing else changes (invalid pixels are not averaged).
TEST(stereoGatedMean, VectorAndPixelLoopsGiveTheSameFloats) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> noise(-0.6f, 0.6f);
  cv::Mat d(9, 45, CV_32F);
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x)
      d.at<float>(y, x) = rng() % 6 == 0 ? 0.0f : 4.0f + 9.0f * ((x / 6) % 3) + noise(rng);
  for (const GatedMeanParams p : {GatedMeanParams{2, 0.5f, 0.05f}, GatedMeanParams{3, 0.3f, 0.1f}}) {
    const cv::Mat a = run(d, p);
    for (int s = 1; s <= 8; ++s) {
      cv::Mat shifted = cv::Mat::zeros(d.rows, d.cols + s, CV_32F);
      d.copyTo(shifted(cv::Rect(s, 0, d.cols, d.rows)));
      const cv::Mat b = run(shifted, p)(cv::Rect(s, 0, d.cols, d.rows));
      for (int y = 0; y < d.rows; ++y)
        for (int x = 0; x < d.cols; ++x)
          ASSERT_EQ(a.at<float>(y, x), b.at<float>(y, x)) << "shift " << s << " at " << x << "," << y;
    }
  }
}

TEST(stereoGatedMean, KeepsDepthEdgesAndHolesAndAPlane) {
  // a slanted plane (disparity linear in x and y) with a nearer box in front and a hole
  cv::Mat d(40, 60, CV_32F);
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) d.at<float>(y, x) = 20.0f + 0.05f * x + 0.1f * y;
  d(cv::Rect(20, 10, 15, 20)).setTo(30.0f);  // 10 px nearer: outside any gate
  d(cv::Rect(45, 30, 3, 3)).setTo(0.0f);
  const cv::Mat out = run(d, GatedMeanParams{});
  // the box's pixels at its border mix nothing of the plane behind
  for (int y = 10; y < 30; ++y) {
    EXPECT_FLOAT_EQ(out.at<float>(y, 20), 30.0f);
    EXPECT_FLOAT_EQ(out.at<float>(y, 34), 30.0f);
  }
  // the plane's interior (whole windows on it) stays the plane
  for (int y = 2; y < 8; ++y)
    for (int x = 2; x < 58; ++x) EXPECT_NEAR(out.at<float>(y, x), d.at<float>(y, x), 1e-4f) << x << "," << y;
  // holes stay holes
  EXPECT_EQ(cv::countNonZero(out(cv::Rect(45, 30, 3, 3))), 0);
}

TEST(stereoGatedMean, TheGateIsAShareOfTheDisparity) {
  // two surfaces 1 px apart in one window: at 10 px that is 10 % of the depth (kept apart by a
  // 5 % gate), at 40 px 2.5 % (averaged)
  for (const float base : {10.0f, 40.0f}) {
    cv::Mat d(9, 9, CV_32F, cv::Scalar(base));
    d.colRange(5, 9).setTo(base + 1.0f);
    const cv::Mat out = run(d, GatedMeanParams{2, 0.5f, 0.05f});
    if (base < 20)
      EXPECT_FLOAT_EQ(out.at<float>(4, 4), base) << "1 px at 10 px is a depth edge";
    else
      EXPECT_GT(out.at<float>(4, 4), base + 0.1f) << "1 px at 40 px is scatter on one surface";
  }
}

TEST(stereoGatedMean, RowRangesGiveTheResultOfOneCall) {
  std::mt19937 rng(9);
  cv::Mat d(31, 50, CV_32F);
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) d.at<float>(y, x) = rng() % 6 == 0 ? 0.0f : 12.0f + (rng() % 100) / 100.0f;
  const GatedMeanParams p;
  const cv::Mat whole = run(d, p);
  cv::Mat parts = d.clone();
  gatedMeanRows(d, parts, p, 0, 13);
  gatedMeanRows(d, parts, p, 13, 31);
  EXPECT_EQ(cv::countNonZero(whole != parts), 0);
  EXPECT_EQ(cv::countNonZero(run(d, GatedMeanParams{0, 0.5f, 0.05f}) != d), 0) << "radius 0 is off";
}

TEST(stereoGatedMean, KeysAreReadAndRangeChecked) {
  EXPECT_EQ(Params{}.gated_mean_radius, 2) << "on by default";
  nerv::ConfigSection ok(YAML::Load("{gated_mean_radius: 0, gated_mean_range_px: 1.0, gated_mean_range_rel: 0.1}"),
                         "stereo_matcher");
  const Params p = readParams(ok);
  EXPECT_EQ(p.gated_mean_radius, 0);
  EXPECT_DOUBLE_EQ(p.gated_mean_range_px, 1.0);
  EXPECT_DOUBLE_EQ(p.gated_mean_range_rel, 0.1);
  for (const char* bad : {"{gated_mean_radius: 9}", "{gated_mean_range_rel: 2}", "{gated_mean_range_px: -1}"}) {
    nerv::ConfigSection s(YAML::Load(bad), "stereo_matcher");
    try {
      readParams(s);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const nerv::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("gated_mean_"), std::string::npos) << e.what();
    }
  }
}

TEST(stereoGatedMean, TheMatcherAppliesItAfterItsFilters) {
  // random texture shifted by 8 px: the default matcher's output with the filter is the
  // output without it, filtered
  std::mt19937 rng(2);
  cv::Mat right(60, 160, CV_8U), left(60, 160, CV_8U);
  for (int y = 0; y < right.rows; ++y)
    for (int x = 0; x < right.cols; ++x) right.at<uint8_t>(y, x) = static_cast<uint8_t>(rng() % 256);
  for (int y = 0; y < left.rows; ++y)
    for (int x = 0; x < left.cols; ++x) left.at<uint8_t>(y, x) = right.at<uint8_t>(y, std::max(0, x - 8));
  Params with;
  with.num_disparities = 32;
  Params without = with;
  without.gated_mean_radius = 0;
  cv::Mat a, b;
  StereoMatcher::create(with)->compute(left, right, a);
  StereoMatcher::create(without)->compute(left, right, b);
  const cv::Mat expected = run(b, GatedMeanParams{});
  EXPECT_EQ(cv::countNonZero(a != expected), 0);
  EXPECT_GT(cv::countNonZero(b > 0), b.total() / 2) << "the matcher found the shift";
}

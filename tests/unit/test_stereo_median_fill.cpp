// nerv_sgm's median + isolated-hole fill (median_fill.hpp) against a plain
// per-pixel reference, over the whole map and split into row ranges (the
// matcher runs two halves in parallel).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "median_fill.hpp"
#include "stereo_reference_median_fill.hpp"

using namespace nerv::stereo;

TEST(stereoMedianFill, MatchesThePlainReferenceWholeAndInRowRanges) {
  std::mt19937 rng(5);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  int filled = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const int rows = uniform(1, 60), cols = uniform(1, 90);
    cv::Mat d(rows, cols, CV_32F), c(rows, cols, CV_32F);
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) {
        const int e = uniform(0, 99);
        d.at<float>(y, x) = e < 12 ? 0.0f : 20.0f + uniform(-30, 30) / 16.0f + (e < 15 ? 12.0f : 0.0f);
        c.at<float>(y, x) = uniform(1, 1000) / 1000.0f;
      }
    cv::Mat ref_d, ref_c;
    referenceMedianFill(d, c, ref_d, ref_c);
    filled += cv::countNonZero((d == 0) & (ref_d > 0));
    // Whole map in one call, then split into up to three ranges with the same `before`.
    for (int split = 0; split < 2; ++split) {
      cv::Mat before = d.clone(), out_d = d.clone(), out_c = c.clone(), scratch;
      if (split == 0) {
        medianFillRows(before, out_d, out_c, 0, rows, scratch);
      } else {
        const int a = uniform(0, rows), b = uniform(a, rows);
        medianFillRows(before, out_d, out_c, b, rows, scratch);  // out of order on purpose
        medianFillRows(before, out_d, out_c, 0, a, scratch);
        medianFillRows(before, out_d, out_c, a, b, scratch);
      }
      ASSERT_EQ(cv::norm(out_d, ref_d, cv::NORM_INF), 0.0) << "trial " << trial << " split " << split;
      ASSERT_EQ(cv::norm(out_c, ref_c, cv::NORM_INF), 0.0) << "trial " << trial << " split " << split;
    }
  }
  EXPECT_GT(filled, 200) << "the random maps hardly exercise the fill";
}

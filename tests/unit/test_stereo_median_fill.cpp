// nerv_sgm's median + isolated-hole fill (median_fill.hpp) against a plain
// per-pixel reference, over the whole map and split into row ranges (the
// matcher runs two halves in parallel).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "median_fill.hpp"

using namespace nerv::stereo;

namespace {

// Per pixel: the 3x3 median (replicated border, invalid = 0 counted) replaces
// a valid pixel; an invalid pixel inside the image takes it when at least 6 of
// its 8 neighbours are valid, with the lowest of their confidences (>= 1e-3).
void referenceMedianFill(const cv::Mat& d, const cv::Mat& c, cv::Mat& out_d, cv::Mat& out_c) {
  out_d = d.clone();
  out_c = c.clone();
  auto at = [&](int y, int x) { return d.at<float>(std::clamp(y, 0, d.rows - 1), std::clamp(x, 0, d.cols - 1)); };
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) {
      std::vector<float> w;
      int valid = 0;
      float lowest = 1.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          w.push_back(at(y + dy, x + dx));
          if ((dy || dx) && at(y + dy, x + dx) > 0) {
            ++valid;
            lowest = std::min(lowest, c.at<float>(std::clamp(y + dy, 0, d.rows - 1), std::clamp(x + dx, 0, d.cols - 1)));
          }
        }
      std::nth_element(w.begin(), w.begin() + 4, w.end());
      const float m = w[4];
      if (!(m > 0)) continue;
      const bool inner = y > 0 && x > 0 && y + 1 < d.rows && x + 1 < d.cols;
      if (d.at<float>(y, x) > 0) {
        out_d.at<float>(y, x) = m;
      } else if (inner && valid >= 6) {
        out_d.at<float>(y, x) = m;
        out_c.at<float>(y, x) = std::max(lowest, 1e-3f);
      }
    }
}

}  // namespace

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

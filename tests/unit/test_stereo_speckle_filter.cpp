// Speckle removal against the plain reference: OpenCV's filterSpeckles on the
// same fixed-point map, on random disparity maps and stripes of them.
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <random>

#include "speckle_filter.hpp"

using namespace nerv::stereo;

namespace {

// What removeSpeckles did before it had its own region search.
void referenceRemoveSpeckles(cv::Mat& disparity, cv::Mat& confidence, int window_px, int range_px,
                             int row_begin, int row_end) {
  cv::Mat stripe = disparity.rowRange(row_begin, row_end), fixed, buf;
  stripe.convertTo(fixed, CV_16S, 16.0);
  cv::filterSpeckles(fixed, 0, window_px, range_px * 16, buf);
  for (int y = 0; y < stripe.rows; ++y)
    for (int x = 0; x < stripe.cols; ++x)
      if (fixed.at<int16_t>(y, x) == 0) {
        stripe.at<float>(y, x) = 0.0f;
        confidence.at<float>(row_begin + y, x) = 0.0f;
      }
}

}  // namespace

// Blobs of random size and level on a smooth background with holes, noise of
// a few 1/16 px (differences right at the range occur) and sub-1/32 px
// values that round to invalid.
TEST(stereoSpeckleFilter, MatchesOpenCvFilterSpecklesOnRandomMaps) {
  std::mt19937 rng(3);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  SpeckleScratch scratch;  // reused across calls, as in the matcher
  int total_removed = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int rows = uniform(1, 90), cols = uniform(1, 160);
    cv::Mat disp(rows, cols, CV_32F);
    const float base = uniform(16, 600) / 16.0f, slope = uniform(-4, 4) / 64.0f;
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) disp.at<float>(y, x) = std::max(0.0f, base + slope * (x - y));
    for (int b = uniform(0, 40); b > 0; --b) {  // blobs: rectangles with ragged edges, or holes
      const int w = uniform(1, 16), h = uniform(1, 16), x0 = uniform(0, cols - 1), y0 = uniform(0, rows - 1);
      const float level = uniform(0, 3) == 0 ? 0.0f : uniform(16, 1000) / 16.0f;
      for (int y = y0; y < std::min(rows, y0 + h); ++y)
        for (int x = x0; x < std::min(cols, x0 + w); ++x)
          if (uniform(0, 9) > 0) disp.at<float>(y, x) = level;
    }
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) {
        float& d = disp.at<float>(y, x);
        const int e = uniform(0, 99);
        if (e < 10 && d > 0.0f) d = std::max(0.0f, d + uniform(-40, 40) / 16.0f);  // noise up to 2.5 px
        else if (e < 13) d = 0.0f;
        else if (e < 14) d = uniform(1, 60) / 2048.0f;  // below 1/32 px: rounds to 0
      }
    const int window = std::vector<int>{100, 1, 0, 20, 5000}[static_cast<size_t>(trial % 5)];
    const int range = trial % 3 == 0 ? 1 : 2;
    const int begin = trial % 2 ? uniform(0, rows - 1) : 0, end = trial % 2 ? uniform(begin, rows) : rows;
    cv::Mat conf(rows, cols, CV_32F, 0.5f), ref_d = disp.clone(), ref_c = conf.clone();
    removeSpeckles(disp, &conf, window, range, begin, end, scratch);
    if (window > 0) referenceRemoveSpeckles(ref_d, ref_c, window, range, begin, end);
    ASSERT_EQ(cv::norm(disp, ref_d, cv::NORM_INF), 0.0) << "trial " << trial;
    ASSERT_EQ(cv::norm(conf, ref_c, cv::NORM_INF), 0.0) << "trial " << trial;
    total_removed += cv::countNonZero(conf != 0.5f);
  }
  EXPECT_GT(total_removed, 5000) << "the random maps hardly exercise the filter";
}

// box_resample.hpp: the block mean and its nearest-neighbour inverse against plain
// per-pixel loops, on sizes that are and are not multiples of the factor.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "box_resample.hpp"
#include "stereo_matcher.hpp"

using namespace nerv::stereo;

namespace {

cv::Mat noise(int rows, int cols, uint64_t seed) {
  cv::Mat m(rows, cols, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  return m;
}

// The mean of the pixels of each block that exist, rounded half up, in doubles.
cv::Mat referenceMean(const cv::Mat& src, int k) {
  cv::Mat out((src.rows + k - 1) / k, (src.cols + k - 1) / k, CV_8UC1);
  for (int by = 0; by < out.rows; ++by)
    for (int bx = 0; bx < out.cols; ++bx) {
      double sum = 0;
      int n = 0;
      for (int y = by * k; y < std::min(src.rows, by * k + k); ++y)
        for (int x = bx * k; x < std::min(src.cols, bx * k + k); ++x) {
          sum += src.at<uint8_t>(y, x);
          ++n;
        }
      out.at<uint8_t>(by, bx) = static_cast<uint8_t>(std::floor(sum / n + 0.5));
    }
  return out;
}

}  // namespace

TEST(stereoBoxResample, MeanEqualsPlainLoopOnEverySize) {
  for (int k : {1, 2, 3, 4, 5, 16})
    for (cv::Size size : {cv::Size(1242, 375), cv::Size(37, 11), cv::Size(1, 1), cv::Size(64, 32), cv::Size(17, 3)}) {
      const cv::Mat src = noise(size.height, size.width, 7 + k);
      cv::Mat fast;
      boxMeanDownscale(src, k, fast);
      const cv::Mat ref = referenceMean(src, k);
      ASSERT_EQ(fast.size(), ref.size()) << "k " << k << " size " << size;
      EXPECT_EQ(cv::countNonZero(fast != ref), 0) << "k " << k << " size " << size;
    }
}

TEST(stereoBoxResample, ExtremesAndHalvesRoundAsDocumented) {
  // All 255 stays 255 (no overflow of the sums at k = 16); 0 0 / 1 1 rounds up to 1;
  // a partial last block of one column is that column's mean.
  cv::Mat white(32, 32, CV_8UC1, cv::Scalar(255)), out;
  boxMeanDownscale(white, 16, out);
  EXPECT_EQ(cv::countNonZero(out != 255), 0);
  cv::Mat m = (cv::Mat_<uint8_t>(2, 3) << 0, 1, 10, 1, 0, 13);
  boxMeanDownscale(m, 2, out);
  ASSERT_EQ(out.size(), cv::Size(2, 1));
  EXPECT_EQ(out.at<uint8_t>(0, 0), 1);   // (0 + 1 + 1 + 0) / 4 = 0.5 -> 1
  EXPECT_EQ(out.at<uint8_t>(0, 1), 12);  // (10 + 13) / 2 = 11.5 -> 12
}

TEST(stereoBoxResample, ExactFactorAgreesWithInterArea) {
  // Where the sides are multiples of k, OpenCV's INTER_AREA is the same block mean; at
  // k = 2 byte for byte. At k = 4 it takes a float path that rounds an exact half to
  // even (cvRound), this one rounds it up: they differ by one level where the sum of the
  // 16 pixels is 8 modulo 16 and its mean's whole part is even, and nowhere else.
  const cv::Mat src = noise(376, 1240, 3);
  for (int k : {2, 4}) {
    cv::Mat ours, theirs;
    boxMeanDownscale(src, k, ours);
    cv::resize(src, theirs, ours.size(), 0, 0, cv::INTER_AREA);
    int differ = 0, explained = 0;
    for (int by = 0; by < ours.rows; ++by)
      for (int bx = 0; bx < ours.cols; ++bx) {
        if (ours.at<uint8_t>(by, bx) == theirs.at<uint8_t>(by, bx)) continue;
        ++differ;
        int sum = 0;
        for (int y = 0; y < k; ++y)
          for (int x = 0; x < k; ++x) sum += src.at<uint8_t>(by * k + y, bx * k + x);
        const int n = k * k;
        if (sum % n == n / 2 && (sum / n) % 2 == 0 && theirs.at<uint8_t>(by, bx) == sum / n &&
            ours.at<uint8_t>(by, bx) == sum / n + 1)
          ++explained;
      }
    if (k == 2) {
      EXPECT_EQ(differ, 0);
    }
    EXPECT_EQ(explained, differ) << "k " << k;
  }
}

TEST(stereoBoxResample, UpscaleRepeatsEachValueOverItsBlock) {
  for (int k : {1, 2, 4, 3})
    for (cv::Size size : {cv::Size(1242, 375), cv::Size(5, 7), cv::Size(1, 1)}) {
      const cv::Size small((size.width + k - 1) / k, (size.height + k - 1) / k);
      cv::Mat f(small, CV_32FC1), u8 = noise(small.height, small.width, 11), c3(small, CV_8UC3);
      cv::RNG rng(5);
      rng.fill(f, cv::RNG::UNIFORM, -100.0, 100.0);
      rng.fill(c3, cv::RNG::UNIFORM, 0, 256);
      f.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();  // bits kept, not compared by value
      cv::Mat fo, uo, co;
      blockNearestUpscale(f, k, size, fo);
      blockNearestUpscale(u8, k, size, uo);
      blockNearestUpscale(c3, k, size, co);
      ASSERT_EQ(fo.size(), size);
      ASSERT_EQ(co.type(), CV_8UC3);
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
          EXPECT_EQ(std::memcmp(&fo.at<float>(y, x), &f.at<float>(y / k, x / k), sizeof(float)), 0);
          EXPECT_EQ(uo.at<uint8_t>(y, x), u8.at<uint8_t>(y / k, x / k));
          EXPECT_EQ(co.at<cv::Vec3b>(y, x), c3.at<cv::Vec3b>(y / k, x / k));
        }
    }
}

TEST(stereoBoxResample, InPlaceCallsReadTheirInput) {
  cv::Mat m = noise(9, 9, 1), copy = m.clone();
  boxMeanDownscale(m, 2, m);
  EXPECT_EQ(cv::countNonZero(m != referenceMean(copy, 2)), 0);
  cv::Mat f(5, 5, CV_32FC1, cv::Scalar(2.5f));
  blockNearestUpscale(f, 2, cv::Size(9, 9), f);
  ASSERT_EQ(f.size(), cv::Size(9, 9));
  EXPECT_EQ(cv::countNonZero(f != 2.5f), 0);
}

TEST(stereoBoxResample, WrongInputIsRefused) {
  cv::Mat out;
  EXPECT_THROW(boxMeanDownscale(cv::Mat(4, 4, CV_32FC1), 2, out), cv::Exception);
  EXPECT_THROW(boxMeanDownscale(cv::Mat(4, 4, CV_8UC1), 0, out), cv::Exception);
  EXPECT_THROW(blockNearestUpscale(cv::Mat(3, 3, CV_32FC1), 2, cv::Size(8, 8), out), cv::Exception);
}

TEST(stereoBoxResample, HalfResolutionMatchRepeatsEachValueOverItsBlock) {
  // stereo_matcher.downscale 2 on views of odd size (KITTI's 375 rows): every full-
  // resolution value and confidence is the one of its 2 x 2 block's top-left pixel, down to
  // the last row and column, the layout the block mean made the half views in. (At this
  // size OpenCV's nearest-neighbour resize, used before, gave the same layout; its area
  // resize of the views did not, box_resample.hpp.) Also: 32 levels are
  // accepted (16 at half resolution), which the inner matcher's own check once refused.
  const int rows = 375, cols = 241, shift = 12;
  cv::Mat wide(rows, cols + shift, CV_8UC1);
  cv::RNG rng(9);
  rng.fill(wide, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(wide, wide, cv::Size(0, 0), 1.0);
  const cv::Mat left = wide(cv::Rect(0, 0, cols, rows)).clone(), right = wide(cv::Rect(shift, 0, cols, rows)).clone();
  nerv::stereo::Params p;
  p.num_disparities = 32;
  p.downscale = 2;
  cv::Mat disparity, confidence;
  nerv::stereo::StereoMatcher::create(p)->compute(left, right, disparity, confidence);
  ASSERT_EQ(disparity.size(), left.size());
  ASSERT_EQ(confidence.size(), left.size());
  int valid = 0;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) {
      const float d = disparity.at<float>(y, x);
      EXPECT_EQ(std::memcmp(&d, &disparity.at<float>(y & ~1, x & ~1), sizeof d), 0) << y << " " << x;
      EXPECT_EQ(confidence.at<float>(y, x), confidence.at<float>(y & ~1, x & ~1)) << y << " " << x;
      valid += d > 0;
    }
  // and it matched: most of the view at the shift (x2 back to full resolution)
  int right_value = 0;
  for (int y = 0; y < rows; ++y)
    for (int x = 40; x < cols; ++x) right_value += std::abs(disparity.at<float>(y, x) - shift) <= 1.0f;
  EXPECT_GT(right_value, 0.6 * rows * (cols - 40)) << valid << " valid";
}

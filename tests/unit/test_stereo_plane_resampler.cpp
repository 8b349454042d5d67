// The right view's row correction resampled with a separable Lanczos kernel
// (services/stereo_matcher/plane_resampler.hpp): against a plain per-pixel implementation of the
// same formula, exact for whole rows, and sharper than bilinear on a view whose shifted content
// is known exactly.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "plane_resampler.hpp"
#include "stereo_scene_texture.hpp"

namespace nerv::stereo {
namespace {

// The kernel of p's fraction over the eight pixels around p, pixel(i) giving the i-th along the
// line (border repeated by the caller): the plain form of one pass.
template <typename Pixel>
double readAt(double p, Pixel pixel) {
  int base = static_cast<int>(std::floor(p));
  int q = static_cast<int>(std::lround((p - base) * PlaneResampler::kSteps));
  if (q == PlaneResampler::kSteps) ++base, q = 0;
  const int16_t* w = PlaneResampler::weights(q);
  double sum = 0;
  for (int k = 0; k < PlaneResampler::kTaps; ++k) sum += w[k] * static_cast<double>(pixel(base - 3 + k));
  return sum / (1 << PlaneResampler::kShift);
}

uint8_t toByte(double v) { return static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L)); }

// Pixel by pixel: each column read at its row, then each row at its column shift.
cv::Mat reference(const cv::Mat& in, const RowPlane& p) {
  const double cx = 0.5 * in.cols, cy = 0.5 * in.rows;
  cv::Mat columns(in.size(), CV_8UC1), out(in.size(), CV_8UC1);
  for (int y = 0; y < in.rows; ++y)
    for (int x = 0; x < in.cols; ++x)
      columns.at<uint8_t>(y, x) = toByte(readAt(y + p.offset_px + p.slope_x * (x - cx) + p.slope_y * (y - cy),
                                                [&](int r) { return in.at<uint8_t>(std::clamp(r, 0, in.rows - 1), x); }));
  for (int y = 0; y < in.rows; ++y)
    for (int x = 0; x < in.cols; ++x)
      out.at<uint8_t>(y, x) = toByte(readAt(x - p.slope_x * (y - cy),
                                            [&](int c) { return columns.at<uint8_t>(y, std::clamp(c, 0, in.cols - 1)); }));
  return out;
}

cv::Mat resampled(const cv::Mat& in, const RowPlane& p) {
  PlaneResampler r;
  r.set(p, in.size());
  return r.apply(in).clone();
}

TEST(stereoPlaneResampler, TheWeightsSumToOneAndWholePixelsAreCopies) {
  for (int q = 0; q < PlaneResampler::kSteps; ++q) {
    int sum = 0;
    for (int k = 0; k < PlaneResampler::kTaps; ++k) sum += PlaneResampler::weights(q)[k];
    EXPECT_EQ(sum, 1 << PlaneResampler::kShift) << q;
  }
  const int16_t* whole = PlaneResampler::weights(0);
  for (int k = 0; k < PlaneResampler::kTaps; ++k) EXPECT_EQ(whole[k], k == 3 ? 1 << PlaneResampler::kShift : 0);
  // Half a pixel: symmetric about the two middle taps.
  const int16_t* half = PlaneResampler::weights(PlaneResampler::kSteps / 2);
  for (int k = 0; k < PlaneResampler::kTaps / 2; ++k) EXPECT_EQ(half[k], half[PlaneResampler::kTaps - 1 - k]) << k;
}

TEST(stereoPlaneResampler, WholeRowsMoveTheViewExactly) {
  const cv::Mat in = multiScaleTexture(320, 120, 21);
  const cv::Mat out = resampled(in, {2.0, 0, 0});
  for (int y = 0; y < in.rows; ++y) {
    const int from = std::min(y + 2, in.rows - 1);
    EXPECT_EQ(cv::norm(out.row(y), in.row(from), cv::NORM_INF), 0) << y;
  }
  EXPECT_EQ(cv::norm(resampled(in, {}), in, cv::NORM_INF), 0);
}

TEST(stereoPlaneResampler, AsThePlainFormPixelByPixel) {
  const cv::Mat in = multiScaleTexture(333, 101, 22);  // odd sizes: runs and borders off the grid
  for (const RowPlane& p : {RowPlane{0.37, 0, 0}, RowPlane{-1.61, 0.0021, -0.0013}, RowPlane{0.5, -0.004, 0.002},
                            RowPlane{4.2, 0.01, 0}}) {
    const cv::Mat fast = resampled(in, p), plain = reference(in, p);
    EXPECT_LE(cv::norm(fast, plain, cv::NORM_INF), 1) << p.offset_px << " " << p.slope_x << " " << p.slope_y;
    EXPECT_LT(cv::norm(fast, plain, cv::NORM_L1) / in.total(), 0.05) << p.offset_px;
  }
}

// A view whose content is known at any position (a sum of sinusoids up to 0.3 cycles a pixel),
// moved half a row: Lanczos comes within a tenth of bilinear's error, which averages two rows.
TEST(stereoPlaneResampler, SharperThanBilinear) {
  const auto view = [](double dy) {
    cv::Mat m(120, 320, CV_8UC1);
    for (int y = 0; y < m.rows; ++y)
      for (int x = 0; x < m.cols; ++x) {
        const double yy = y + dy;
        const double v = 128 + 40 * std::sin(0.3 * 2 * CV_PI * yy + 0.2 * x) + 30 * std::sin(0.17 * 2 * CV_PI * yy + 1.0) +
                         20 * std::cos(0.07 * 2 * CV_PI * x + 0.11 * 2 * CV_PI * yy);
        m.at<uint8_t>(y, x) = toByte(v);
      }
    return m;
  };
  const cv::Mat in = view(0), truth = view(0.5);
  const cv::Mat lanczos = resampled(in, {0.5, 0, 0});
  cv::Mat bilinear;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 0, 0, 1, 0.5);
  cv::warpAffine(in, bilinear, shift, in.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  const cv::Rect inner(8, 8, in.cols - 16, in.rows - 16);
  const double e_lanczos = cv::norm(lanczos(inner), truth(inner), cv::NORM_L1) / inner.area();
  const double e_bilinear = cv::norm(bilinear(inner), truth(inner), cv::NORM_L1) / inner.area();
  EXPECT_LT(e_lanczos, 0.1 * e_bilinear) << e_lanczos << " against " << e_bilinear;
  EXPECT_LT(e_lanczos, 2.0);
}

}  // namespace
}  // namespace nerv::stereo

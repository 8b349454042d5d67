// Requantized gray: the luma of a color image quantized at a chosen offset,
// against hand-computed levels and against OpenCV's own conversion.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <stdexcept>

#include "gray_requantize.hpp"

using namespace nerv;

TEST(toolsGrayRequantize, LevelsOfAKnownColor) {
  // B 30, G 100, R 200: luma 0.114 * 30 + 0.587 * 100 + 0.299 * 200 = 3.42 + 58.7 + 59.8 = 121.92.
  const cv::Mat bgr(2, 3, CV_8UC3, cv::Scalar(30, 100, 200));
  EXPECT_EQ(requantizedGray(bgr, 0.0).at<uint8_t>(1, 2), 121);
  EXPECT_EQ(requantizedGray(bgr, 0.07).at<uint8_t>(0, 0), 121);
  EXPECT_EQ(requantizedGray(bgr, 0.09).at<uint8_t>(0, 0), 122);
  EXPECT_EQ(requantizedGray(bgr, 0.5).at<uint8_t>(0, 1), 122);
  // White stays 255 at every offset, black 0.
  const cv::Mat white(1, 1, CV_8UC3, cv::Scalar(255, 255, 255)), black(1, 1, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_EQ(requantizedGray(white, 0.99).at<uint8_t>(0, 0), 255);
  EXPECT_EQ(requantizedGray(black, 0.99).at<uint8_t>(0, 0), 0);
}

TEST(toolsGrayRequantize, EveryOffsetIsWithinOneLevelOfOpenCvsGray) {
  cv::Mat bgr(40, 64, CV_8UC3);
  cv::randu(bgr, cv::Scalar::all(0), cv::Scalar::all(256));
  cv::Mat reference;
  cv::cvtColor(bgr, reference, cv::COLOR_BGR2GRAY);
  int differing_at_half = 0;
  for (double offset : {0.0, 0.25, 0.5, 0.75, 0.999}) {
    const cv::Mat g = requantizedGray(bgr, offset);
    ASSERT_EQ(g.type(), CV_8UC1);
    ASSERT_EQ(g.size(), bgr.size());
    cv::Mat diff;
    cv::absdiff(g, reference, diff);
    double worst = 0;
    cv::minMaxLoc(diff, nullptr, &worst);
    EXPECT_LE(worst, 1) << "offset " << offset;
    if (offset == 0.5) differing_at_half = cv::countNonZero(diff);
  }
  // Offset 0.5 rounds as cv::cvtColor does; its fixed-point weights differ from
  // the exact ones in the last bits, so allow a few pixels near a half level.
  EXPECT_LT(differing_at_half, bgr.total() / 50);
  // Offsets 0 and 0.999 differ on almost every pixel whose luma is not an integer.
  cv::Mat lo_hi;
  cv::absdiff(requantizedGray(bgr, 0.0), requantizedGray(bgr, 0.999), lo_hi);
  EXPECT_GT(cv::countNonZero(lo_hi), static_cast<int>(bgr.total() * 0.9));
}

TEST(toolsGrayRequantize, RejectsGrayInputAndOffsetsOutsideTheUnitInterval) {
  EXPECT_THROW(requantizedGray(cv::Mat(4, 4, CV_8UC1, cv::Scalar(9)), 0.5), std::invalid_argument);
  const cv::Mat bgr(4, 4, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_THROW(requantizedGray(bgr, 1.0), std::invalid_argument);
  EXPECT_THROW(requantizedGray(bgr, -0.1), std::invalid_argument);
  EXPECT_THROW(requantizedGray(bgr, std::nan("")), std::invalid_argument);
}

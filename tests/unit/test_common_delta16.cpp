// The delta16 disparity encoding (delta16_codec.hpp): lossless on maps with
// holes, jumps and the uint16 extremes; about a byte a pixel on a surface; a
// broken stream (short, long, over-long varint, out-of-range value) is a named
// error, never a read outside it; through the DISPARITY message it decodes to
// what u16le does, and checkDisparity bounds its size before decoding.
#include <gtest/gtest.h>

#include <random>

#include "delta16_codec.hpp"
#include "message_check.hpp"
#include "message_convert.hpp"

using namespace nerv;

namespace {

cv::Mat randomMap(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  cv::Mat m(h, w, CV_16U);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const unsigned k = rng() % 10;
      m.at<uint16_t>(v, u) = k == 0 ? 0 : k == 1 ? 65535 : k < 5 ? static_cast<uint16_t>(rng()) : 3000 + u * 7 + v;
    }
  return m;
}

}  // namespace

TEST(commonDelta16, RoundTripIsLossless) {
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 1), cv::Size(1, 9), cv::Size(64, 33), cv::Size(321, 17)}) {
    const cv::Mat m = randomMap(size.width, size.height, 7u + size.width);
    std::vector<uint8_t> bytes;
    encodeDelta16(m, bytes);
    EXPECT_GE(bytes.size(), delta16MinBytes(size.width, size.height));
    EXPECT_LE(bytes.size(), delta16MaxBytes(size.width, size.height));
    cv::Mat back;
    ASSERT_EQ(decodeDelta16(bytes.data(), bytes.size(), size.width, size.height, back), "") << size;
    EXPECT_EQ(cv::norm(m, back, cv::NORM_INF), 0.0) << size;
  }
}

TEST(commonDelta16, ASurfaceTakesAboutAByteAPixel) {
  // A slanted road's disparity at the wire's 1/256 px: steps of a fraction of a pixel.
  cv::Mat m(200, 300, CV_16U);
  for (int v = 0; v < m.rows; ++v)
    for (int u = 0; u < m.cols; ++u) m.at<uint16_t>(v, u) = static_cast<uint16_t>(256 * (10 + 0.3 * v) + (u * 13) % 40);
  std::vector<uint8_t> bytes;
  encodeDelta16(m, bytes);
  EXPECT_LT(bytes.size(), m.total() * 11 / 10);
}

TEST(commonDelta16, BrokenStreamsAreNamedErrors) {
  const cv::Mat m = randomMap(40, 10, 3);
  std::vector<uint8_t> bytes;
  encodeDelta16(m, bytes);
  cv::Mat out;
  // Short: every truncation fails (the decoder stops at the end it was given).
  for (size_t n : {size_t{0}, size_t{1}, bytes.size() / 2, bytes.size() - 1}) {
    std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    EXPECT_NE(decodeDelta16(cut.data(), cut.size(), 40, 10, out).find("ends at row"), std::string::npos) << n;
  }
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_NE(decodeDelta16(longer.data(), longer.size(), 40, 10, out).find("after the last pixel"), std::string::npos);
  const std::vector<uint8_t> overlong = {0x80, 0x80, 0x80, 0x01};
  EXPECT_NE(decodeDelta16(overlong.data(), overlong.size(), 1, 1, out).find("over 3 bytes"), std::string::npos);
  const std::vector<uint8_t> negative = {0x01};  // zigzag 1 = -1 from 0
  EXPECT_NE(decodeDelta16(negative.data(), negative.size(), 1, 1, out).find("not a uint16"), std::string::npos);
  const std::vector<uint8_t> too_big = {0xfe, 0xff, 0x07};  // +65535 twice
  const std::vector<uint8_t> two = {0xfe, 0xff, 0x07, 0xfe, 0xff, 0x07};
  EXPECT_EQ(decodeDelta16(too_big.data(), too_big.size(), 1, 1, out), "");
  EXPECT_EQ(out.at<uint16_t>(0, 0), 65535);
  EXPECT_NE(decodeDelta16(two.data(), two.size(), 2, 1, out).find("not a uint16"), std::string::npos);
  EXPECT_NE(decodeDelta16(bytes.data(), bytes.size(), 0, 10, out), "");
}

TEST(commonDelta16, TheDisparityMessageDecodesAsU16leAndIsSizeChecked) {
  cv::Mat disparity(48, 64, CV_32F);
  std::mt19937 rng(5);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u)
      disparity.at<float>(v, u) = (rng() % 7 == 0) ? 0.0f : 5.0f + 0.01f * static_cast<float>(rng() % 3000);
  disparity_t raw, packed;
  encodeDisparity(disparity, "u16le", raw);
  encodeDisparity(disparity, "delta16", packed);
  EXPECT_EQ(packed.encoding, "delta16");
  EXPECT_LT(packed.data.size(), raw.data.size());
  const StereoCamera cam{64, 48, 60, 60, 32, 24, 0.5};  // width, height, fx, fy, cx, cy, baseline
  for (disparity_t* m : {&raw, &packed}) {
    m->calib = toCalibration(cam);
    encodeConfidence(cv::Mat(), *m);
  }
  const Limits limits;
  EXPECT_FALSE(checkDisparity(packed, limits)) << checkDisparity(packed, limits).counter << ": " << checkDisparity(packed, limits).message;
  cv::Mat a, b;
  ASSERT_EQ(decodeDisparity(raw, a), "");
  ASSERT_EQ(decodeDisparity(packed, b), "");
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);

  disparity_t small = packed;  // fewer bytes than one a pixel: refused before decoding
  small.data.resize(static_cast<size_t>(small.width) * small.height - 1);
  small.size = static_cast<int32_t>(small.data.size());
  const Problem p = checkDisparity(small, limits);
  EXPECT_EQ(p.counter, "bad_size");
  EXPECT_NE(p.message.find("delta16 disparity needs"), std::string::npos) << p.message;
}

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "message_check.hpp"
#include "message_convert.hpp"

using namespace nerv;

namespace {

StereoCamera smallCamera() {
  StereoCamera c;
  c.width = 64;
  c.height = 32;
  c.fx = c.fy = 50;
  c.cx = 32;
  c.cy = 16;
  c.baseline_m = 0.5;
  return c;
}

stereo_frame_t goodFrame() {
  stereo_frame_t f;
  f.header.seq = 3;
  f.header.utime = 1000;
  f.calib = toCalibration(smallCamera());
  cv::Mat img(32, 64, CV_8UC1);
  cv::randu(img, 0, 255);
  f.left = encodeImage(img, "gray8");
  f.right = encodeImage(img, "png");
  return f;
}

disparity_t goodDisparity() {
  disparity_t d;
  d.calib = toCalibration(smallCamera());
  cv::Mat disp(32, 64, CV_32F, cv::Scalar(12.25f));
  encodeDisparity(disp, "u16le", d);
  encodeConfidence(cv::Mat(), d);
  return d;
}

}  // namespace

TEST(commonMessageCheck, GoodMessagesPass) {
  EXPECT_FALSE(checkStereoFrame(goodFrame(), Limits{}));
  EXPECT_FALSE(checkDisparity(goodDisparity(), Limits{}));
}

TEST(commonMessageCheck, SizeFieldMustMatchData) {
  stereo_frame_t f = goodFrame();
  f.left.size += 1;
  Problem p = checkStereoFrame(f, Limits{});
  EXPECT_EQ(p.counter, "bad_size");
  EXPECT_NE(p.message.find("left"), std::string::npos);
  disparity_t d = goodDisparity();
  d.data.pop_back();
  EXPECT_EQ(checkDisparity(d, Limits{}).counter, "bad_size");
}

TEST(commonMessageCheck, DimensionsWithinLimits) {
  stereo_frame_t f = goodFrame();
  Limits small;
  small.max_width = 32;
  EXPECT_EQ(checkStereoFrame(f, small).counter, "bad_size");
}

TEST(commonMessageCheck, LeftRightAndCalibrationSizesMustAgree) {
  stereo_frame_t f = goodFrame();
  cv::Mat other(30, 64, CV_8UC1, cv::Scalar(1));
  f.right = encodeImage(other, "gray8");
  EXPECT_EQ(checkStereoFrame(f, Limits{}).counter, "size_mismatch");
  f = goodFrame();
  f.calib.width = 100;
  EXPECT_EQ(checkStereoFrame(f, Limits{}).counter, "size_mismatch");
}

TEST(commonMessageCheck, NonFiniteCalibrationIsRejected) {
  stereo_frame_t f = goodFrame();
  f.calib.fx = NAN;
  EXPECT_EQ(checkStereoFrame(f, Limits{}).counter, "bad_calibration");
  f = goodFrame();
  f.calib.baseline_m = -0.5;
  EXPECT_EQ(checkStereoFrame(f, Limits{}).counter, "bad_calibration");
  disparity_t d = goodDisparity();
  d.calib.cy = INFINITY;
  EXPECT_EQ(checkDisparity(d, Limits{}).counter, "bad_calibration");
}

TEST(commonMessageCheck, UnknownEncodingsAreRejected) {
  stereo_frame_t f = goodFrame();
  f.left.encoding = "webp";
  EXPECT_EQ(checkStereoFrame(f, Limits{}).counter, "bad_encoding");
  disparity_t d = goodDisparity();
  d.encoding = "float32";
  EXPECT_EQ(checkDisparity(d, Limits{}).counter, "bad_encoding");
}

TEST(commonMessageCheck, StixelsCountsAndNumbers) {
  stixels_t s{};
  s.ground = toMessage(GroundModel{});
  s.num_stixels = 1;  // but no stixels
  s.num_rois = 0;
  EXPECT_EQ(checkStixels(s, Limits{}).counter, "bad_size");
  s.num_stixels = 0;
  EXPECT_FALSE(checkStixels(s, Limits{}));
  Hypothesis h;
  h.box = {1, 2, 3, 4};
  h.z_m = NAN;
  s.rois.push_back(toMessage(h));
  s.num_rois = 1;
  EXPECT_EQ(checkStixels(s, Limits{}).counter, "bad_value");
  // nearest_z_m is checked too, and carried through STIXELS into DETECTIONS.
  h.z_m = 12.0f;
  h.nearest_z_m = NAN;
  s.rois[0] = toMessage(h);
  EXPECT_EQ(checkStixels(s, Limits{}).counter, "bad_value");
  h.nearest_z_m = 11.25f;
  s.rois[0] = toMessage(h);
  EXPECT_FALSE(checkStixels(s, Limits{}));
  EXPECT_FLOAT_EQ(fromMessage(s.rois[0]).nearest_z_m, 11.25f);
  EXPECT_FLOAT_EQ(toDetection(fromMessage(s.rois[0]), Verdict{}).nearest_z_m, 11.25f);
  // So is its uncertainty: finite and not negative.
  for (const float bad : {NAN, INFINITY, -0.1f}) {
    h.nearest_z_sigma_m = bad;
    s.rois[0] = toMessage(h);
    EXPECT_EQ(checkStixels(s, Limits{}).counter, "bad_value") << bad;
  }
  h.nearest_z_sigma_m = 0.11f;
  s.rois[0] = toMessage(h);
  EXPECT_FALSE(checkStixels(s, Limits{}));
  EXPECT_FLOAT_EQ(toDetection(fromMessage(s.rois[0]), Verdict{}).nearest_z_sigma_m, 0.11f);
  surface_normals_t n;
  n.num_rois = 1;
  n.rois.push_back(toMessage(NormalStats{}));
  n.rois[0].ground_fraction = INFINITY;
  EXPECT_EQ(checkSurfaceNormals(n).counter, "bad_value");
}

TEST(commonMessageCheck, StixelsObservedFreeSpace) {
  ObservedFreeSpace o;
  o.column_width_px = 5;
  o.observed = {1.0f, 0.0f, 0.25f};
  o.min_observed = 0.3f;
  o.observed_share = 0.5f;
  o.num_unobserved = 2;
  stixels_t s = stixelsMessage(header_t{}, GroundModel{}, {}, {}, 1.0f, o);
  EXPECT_EQ(s.num_columns, 3);
  EXPECT_EQ(s.column_width_px, 5);
  EXPECT_FLOAT_EQ(s.observed[2], 0.25f);
  EXPECT_EQ(s.num_unobserved, 2);
  EXPECT_FALSE(checkStixels(s, Limits{}));
  s.num_columns = 4;  // but three shares
  EXPECT_EQ(checkStixels(s, Limits{}).counter, "bad_size");
  s.num_columns = 3;
  for (const float bad : {NAN, -0.1f, 1.5f}) {
    stixels_t t = s;
    t.observed[1] = bad;
    EXPECT_EQ(checkStixels(t, Limits{}).counter, "bad_value") << bad;
    t = s;
    t.observed_share = bad;
    EXPECT_EQ(checkStixels(t, Limits{}).counter, "bad_value") << bad;
  }
  stixels_t t = s;
  t.num_unobserved = 4;  // more than the strips
  EXPECT_EQ(checkStixels(t, Limits{}).counter, "bad_value");
  t = s;
  t.column_width_px = 0;  // strips of no width
  EXPECT_EQ(checkStixels(t, Limits{}).counter, "bad_value");
  t = s;
  t.column_width_px = 4000;  // wider than any accepted image
  EXPECT_EQ(checkStixels(t, Limits{}).counter, "bad_value");
  // Messages without the strips (num_columns 0) stay valid.
  EXPECT_FALSE(checkStixels(stixelsMessage(header_t{}, GroundModel{}, {}, {}, 1.0f), Limits{}));
}

TEST(commonMessageConvert, ImagesRoundTripInEveryLosslessEncoding) {
  cv::Mat gray(20, 30, CV_8UC1), bgr(20, 30, CV_8UC3), out;
  cv::randu(gray, 0, 255);
  cv::randu(bgr, 0, 255);
  for (const char* enc : {"gray8", "png"}) {
    ASSERT_EQ(decodeImage(encodeImage(gray, enc), out), "");
    EXPECT_EQ(cv::norm(gray, out, cv::NORM_INF), 0) << enc;
  }
  for (const char* enc : {"bgr8", "png"}) {
    ASSERT_EQ(decodeImage(encodeImage(bgr, enc), out), "");
    EXPECT_EQ(cv::norm(bgr, out, cv::NORM_INF), 0) << enc;
  }
  image_t broken = encodeImage(gray, "png");
  broken.data.resize(10);
  EXPECT_NE(decodeImage(broken, out), "");
}

// The wire's fixed point against the plain per-pixel formula it had before
// it was written branch-free: round half up, 0 for <= 0.5 / scale, NaN, +-inf,
// and 65535 for anything above the range.
TEST(commonMessageConvert, DisparityFixedPointMatchesThePlainFormula) {
  std::vector<float> values = {0.0f, -0.0f, -3.0f, NAN, -NAN, INFINITY, -INFINITY, 1e30f, -1e30f,
                               255.99f, 256.0f, 300.0f, std::numeric_limits<float>::max(),
                               std::numeric_limits<float>::denorm_min()};
  for (int k = 0; k < 4096; ++k) values.push_back(static_cast<float>(k) / (2.0f * kDisparityScale));  // exact halves
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> any(-10.0f, 300.0f);
  while (values.size() % 64 != 0 || values.size() < 20000) values.push_back(any(rng));
  cv::Mat disp(static_cast<int>(values.size() / 64), 64, CV_32F, values.data());
  disparity_t msg;
  encodeDisparity(disp, "u16le", msg);
  ASSERT_EQ(msg.data.size(), 2 * values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const float s = values[i] * kDisparityScale;
    const uint16_t expected =
        (s > 0.5f && std::isfinite(s)) ? static_cast<uint16_t>(std::min(s + 0.5f, 65535.f)) : 0;
    uint16_t got;
    std::memcpy(&got, msg.data.data() + 2 * i, 2);
    ASSERT_EQ(got, expected) << "value " << values[i];
  }
}

TEST(commonMessageConvert, DisparityFixedPointRoundTrip) {
  cv::Mat disp(8, 9, CV_32F);
  cv::randu(disp, 0.0, 200.0);
  disp.at<float>(0, 0) = 0;
  disp.at<float>(1, 1) = -3;
  disp.at<float>(2, 2) = NAN;
  for (const char* enc : {"u16le", "png16"}) {
    disparity_t msg;
    encodeDisparity(disp, enc, msg);
    cv::Mat back;
    ASSERT_EQ(decodeDisparity(msg, back), "");
    EXPECT_EQ(back.at<float>(0, 0), 0);
    EXPECT_EQ(back.at<float>(1, 1), 0);
    EXPECT_EQ(back.at<float>(2, 2), 0);
    for (int v = 3; v < 8; ++v)
      for (int u = 0; u < 9; ++u)
        EXPECT_NEAR(back.at<float>(v, u), disp.at<float>(v, u), 0.5 / kDisparityScale + 1e-6);
  }
}

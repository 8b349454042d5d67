// The display normals and the recomputed pitch distribution against planes
// whose normals are known exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "nerv/ground_model_t.hpp"
#include "normal_needles.hpp"
#include "pitch_distribution.hpp"

using namespace nerv;
using namespace nerv::viz;

namespace {

StereoCamera camera() {
  StereoCamera c;
  c.width = 400, c.height = 300, c.fx = c.fy = 400, c.cx = 200, c.cy = 150, c.baseline_m = 0.5;
  return c;
}

// Ground under a camera at height h pitched down by theta: n = (0, -cos, -sin),
// n.P + h = 0 with P = (u - cx, v - cy, f) B / d gives d = ((v - cy) cos + f sin) B / h.
cv::Mat groundDisparity(const StereoCamera& c, double h, double pitch_deg) {
  const double t = pitch_deg * CV_PI / 180;
  cv::Mat d(c.height, c.width, CV_32F, cv::Scalar(0));
  for (int v = 0; v < c.height; ++v) {
    const double dv = ((v - c.cy) * std::cos(t) + c.fx * std::sin(t)) * c.baseline_m / h;
    if (dv > 0.5) d.row(v).setTo(dv);
  }
  return d;
}

double angleDeg(const cv::Vec3f& a, const cv::Vec3f& b) {
  return std::acos(std::clamp(double(a.dot(b)) / cv::norm(a) / cv::norm(b), -1.0, 1.0)) * 180 / CV_PI;
}

}  // namespace

TEST(renderNeedles, GroundPlaneNormalsAreTheTrueNormalAndClassedGround) {
  const StereoCamera c = camera();
  const double pitch = 3.0;
  const cv::Mat d = groundDisparity(c, 1.5, pitch);
  const double t = pitch * CV_PI / 180;
  const cv::Vec3f truth(0, float(-std::cos(t)), float(-std::sin(t)));
  const auto needles = computeNeedles(d, c, truth, cv::Mat());
  ASSERT_GT(needles.size(), 50u);
  for (const auto& n : needles) {
    // Only rows well inside the plane (the smoothing window sees the horizon edge near it).
    if (n.v < 200) continue;
    EXPECT_LT(angleDeg(n.n, truth), 0.5) << "at " << n.u << "," << n.v;
    EXPECT_EQ(n.cls, NeedleClass::kGround);
  }
}

TEST(renderNeedles, WallsAreObjectOrError) {
  const StereoCamera c = camera();
  // A side wall x = -2 m (plane turned 90 deg from the line of sight): d = -(u - cx) B / 2 for u < cx.
  cv::Mat side(c.height, c.width, CV_32F, cv::Scalar(0));
  for (int u = 0; u < c.cx - 20; ++u) side.col(u).setTo(-(u - c.cx) * c.baseline_m / 2.0);
  const cv::Vec3f up(0, -1, 0);
  auto side_needles = computeNeedles(side, c, up, cv::Mat());
  ASSERT_GT(side_needles.size(), 20u);
  for (const auto& n : side_needles) {
    EXPECT_LT(angleDeg(n.n, {1, 0, 0}), 1.0);
    EXPECT_EQ(n.cls, NeedleClass::kObject);
  }
  // A wall facing the camera (constant disparity): error-like, object-like inside an upright hypothesis.
  const cv::Mat front(c.height, c.width, CV_32F, cv::Scalar(10));
  cv::Mat mask = cv::Mat::zeros(front.size(), CV_8U);
  mask(cv::Rect(0, 0, c.width / 2, c.height)).setTo(255);
  const auto front_needles = computeNeedles(front, c, up, mask);
  ASSERT_GT(front_needles.size(), 20u);
  for (const auto& n : front_needles) {
    EXPECT_LT(angleDeg(n.n, {0, 0, -1}), 0.5);
    EXPECT_EQ(n.cls, n.u < c.width / 2 ? NeedleClass::kObject : NeedleClass::kError) << n.u;
  }
}

TEST(renderNeedles, DepthJumpsAndInvalidPixelsGiveNoNeedle) {
  const StereoCamera c = camera();
  cv::Mat d(c.height, c.width, CV_32F, cv::Scalar(10));
  d.colRange(200, 400).setTo(40);           // a jump at u = 200
  d(cv::Rect(0, 0, 100, 100)).setTo(0);      // invalid corner
  for (const auto& n : computeNeedles(d, c, {0, -1, 0}, cv::Mat())) {
    EXPECT_FALSE(n.u >= 196 && n.u <= 204) << "needle across the jump at u=" << n.u;
    EXPECT_FALSE(n.u < 96 && n.v < 96) << "needle in the invalid corner";
  }
}

TEST(renderNeedles, PitchDistributionPeaksAtTheTruePitch) {
  const StereoCamera c = camera();
  for (double pitch : {-1.0, 0.0, 2.5}) {
    const cv::Mat d = groundDisparity(c, 1.5, pitch);
    const double t = pitch * CV_PI / 180;
    // The v-disparity line of this plane: d = (B cos / h) v + (f sin - cy cos) B / h.
    ground_model_t g{};
    g.valid = true;
    g.vd_slope = float(std::cos(t) * c.baseline_m / 1.5);
    g.vd_intercept = float((c.fx * std::sin(t) - c.cy * std::cos(t)) * c.baseline_m / 1.5);
    const PitchDistribution p = computePitchDistribution(d, c, g);
    ASSERT_GT(p.pitch_deg.size(), 100u) << pitch;
    EXPECT_NEAR(p.mode_deg, pitch, 0.1) << pitch;
    EXPECT_NEAR(p.mean_deg, pitch, 0.1) << pitch;
    double total = 0;
    for (double k : p.counts) total += k;
    EXPECT_EQ(total, double(p.pitch_deg.size()));
  }
  ground_model_t invalid{};
  EXPECT_TRUE(computePitchDistribution(groundDisparity(c, 1.5, 0), c, invalid).pitch_deg.empty());
}

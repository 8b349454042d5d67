#include "warmup_frame.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace nerv {

StereoCamera warmupCamera(const WarmupSize& size) {
  StereoCamera c;
  c.width = size.width;
  c.height = size.height;
  c.fx = c.fy = 0.58 * size.width;
  c.cx = size.width / 2.0;
  c.cy = size.height / 2.0;
  c.baseline_m = 0.54;
  return c;
}

void warmupPair(const WarmupSize& size, cv::Mat& left, cv::Mat& right) {
  left.create(size.height, size.width, CV_8U);
  cv::RNG rng(12345);  // the same frame every start
  rng.fill(left, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(left, left, cv::Size(3, 3), 0);
  right = cv::Mat::zeros(left.size(), CV_8U);
  const int shift = std::min(16, size.width - 1);
  left.colRange(shift, size.width).copyTo(right.colRange(0, size.width - shift));
}

namespace {

constexpr double kHeight = 1.65, kBoxZ = 15.0, kBoxHalfWidth = 1.0, kBoxHeight = 1.5, kWallZ = 40.0;

// Columns [u0, u1) and rows [top, foot) of the box.
cv::Rect boxRect(const StereoCamera& cam) {
  const int u0 = std::max(0, static_cast<int>(cam.cx - cam.fx * kBoxHalfWidth / kBoxZ));
  const int u1 = std::min(cam.width, static_cast<int>(cam.cx + cam.fx * kBoxHalfWidth / kBoxZ) + 1);
  const int foot = std::min(cam.height, static_cast<int>(cam.cy + cam.fy * kHeight / kBoxZ));
  const int top = std::max(0, static_cast<int>(cam.cy + cam.fy * (kHeight - kBoxHeight) / kBoxZ));
  return {u0, top, std::max(0, u1 - u0), std::max(0, foot - top)};
}

}  // namespace

GroundModel warmupGround(const StereoCamera& cam) {
  // A road Y = h below the camera at depth Z = fy h / (v - cy): d = fx B (v - cy) / (fy h).
  GroundModel g;
  g.valid = true;
  g.source = "v_disparity";
  g.vd_slope = static_cast<float>(cam.baseline_m * cam.fx / (cam.fy * kHeight));
  g.vd_intercept = static_cast<float>(-g.vd_slope * cam.cy);
  g.horizon_row = static_cast<float>(cam.cy);
  g.height_m = static_cast<float>(kHeight);
  return g;
}

cv::Mat warmupDisparity(const StereoCamera& cam) {
  const double fb = cam.fx * cam.baseline_m;
  const GroundModel road = warmupGround(cam);
  cv::Mat d(cam.height, cam.width, CV_32F, cv::Scalar(0));
  for (int v = 0; v < cam.height; ++v) {
    float* row = d.ptr<float>(v);
    // The road below the horizon, the wall above it.
    const float value = v > cam.cy ? road.groundDisparity(static_cast<float>(v)) : static_cast<float>(fb / kWallZ);
    std::fill(row, row + cam.width, value);
  }
  const cv::Rect box = boxRect(cam);
  if (box.area() > 0) d(box).setTo(static_cast<float>(fb / kBoxZ));
  return d;
}

std::vector<Hypothesis> warmupHypotheses(const StereoCamera& cam) {
  const cv::Rect r = boxRect(cam);
  Hypothesis h;
  h.box = {r.x, r.y, r.width, r.height};
  h.z_m = h.distance_m = h.nearest_z_m = static_cast<float>(kBoxZ);
  h.width_m = static_cast<float>(2 * kBoxHalfWidth);
  h.height_m = static_cast<float>(kBoxHeight);
  h.disparity = static_cast<float>(cam.fx * cam.baseline_m / kBoxZ);
  h.num_stixels = 1;
  return {h};
}

}  // namespace nerv

#include "normal_needles.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace nerv::viz {

cv::Mat smoothValidDisparity(const cv::Mat& disparity, int window_px) {
  cv::Mat valid = (disparity > 0) & (disparity < 1e6f);  // NaN compares false: invalid
  cv::Mat d = cv::Mat::zeros(disparity.size(), CV_32F);
  disparity.copyTo(d, valid);
  if (window_px <= 1) return d;
  cv::Mat sum, count, valid_f;
  valid.convertTo(valid_f, CV_32F, 1.0 / 255);
  const cv::Size k(window_px, window_px);
  cv::boxFilter(d, sum, CV_32F, k, {-1, -1}, false, cv::BORDER_CONSTANT);
  cv::boxFilter(valid_f, count, CV_32F, k, {-1, -1}, false, cv::BORDER_CONSTANT);
  cv::Mat out = cv::Mat::zeros(disparity.size(), CV_32F);
  for (int v = 0; v < d.rows; ++v) {
    const uint8_t* m = valid.ptr<uint8_t>(v);
    const float* s = sum.ptr<float>(v);
    const float* c = count.ptr<float>(v);
    float* o = out.ptr<float>(v);
    for (int u = 0; u < d.cols; ++u)
      if (m[u] && c[u] > 0.5f) o[u] = s[u] / c[u];
  }
  return out;
}

NeedleClass classifyNeedle(const cv::Vec3f& n, const cv::Vec3f& g, bool upright_roi,
                           const NeedleParams& params) {
  const float to_deg = static_cast<float>(180.0 / CV_PI);
  const float angle_g = std::acos(std::clamp(n.dot(g), -1.0f, 1.0f)) * to_deg;
  if (angle_g <= params.ground_tolerance_deg) return NeedleClass::kGround;
  const bool upright = std::abs(angle_g - 90.0f) <= params.upright_tolerance_deg;
  const float angle_z = std::acos(std::clamp(-n[2], -1.0f, 1.0f)) * to_deg;
  const bool facing = angle_z <= params.facing_cone_deg;
  if (facing) return upright && upright_roi ? NeedleClass::kObject : NeedleClass::kError;
  if (upright) return NeedleClass::kObject;
  return NeedleClass::kOther;
}

std::vector<Needle> computeNeedles(const cv::Mat& disparity, const StereoCamera& cam,
                                   const cv::Vec3f& ground_normal, const cv::Mat& upright_mask,
                                   const NeedleParams& params) {
  std::vector<Needle> out;
  if (disparity.empty() || disparity.type() != CV_32F || params.interval_px < 1 || params.radius_px < 1)
    return out;
  const cv::Mat d = smoothValidDisparity(disparity, params.smooth_px);
  const int r = params.radius_px;
  auto point = [&](int u, int v, float dv) {
    const Point3 p = cam.toPoint(u, v, dv);
    return cv::Vec3f(float(p.x), float(p.y), float(p.z));
  };
  const bool has_mask = !upright_mask.empty() && upright_mask.size() == disparity.size();
  for (int v = r; v < d.rows - r; ++v) {
    if (v % params.interval_px) continue;
    const float* row = d.ptr<float>(v);
    for (int u = r; u < d.cols - r; ++u) {
      if (u % params.interval_px) continue;
      const float dc = row[u];
      if (!(dc > 0)) continue;
      const float dl = row[u - r], dr = row[u + r];
      const float du = d.at<float>(v - r, u), dd = d.at<float>(v + r, u);
      if (!(dl > 0 && dr > 0 && du > 0 && dd > 0)) continue;
      const float jump = params.max_jump_rel * dc + 0.5f;
      if (std::abs(dl - dc) > jump || std::abs(dr - dc) > jump || std::abs(du - dc) > jump ||
          std::abs(dd - dc) > jump)
        continue;
      const cv::Vec3f horizontal = point(u + r, v, dr) - point(u - r, v, dl);
      const cv::Vec3f vertical = point(u, v + r, dd) - point(u, v - r, du);
      cv::Vec3f n = horizontal.cross(vertical);
      const float len = static_cast<float>(cv::norm(n));
      if (!(len > 1e-9f)) continue;
      n /= len;
      Needle needle;
      needle.u = u;
      needle.v = v;
      needle.p = point(u, v, dc);
      if (n.dot(needle.p) > 0) n = -n;  // face the camera
      needle.n = n;
      const bool upright_roi = has_mask && upright_mask.at<uint8_t>(v, u) != 0;
      needle.cls = classifyNeedle(n, ground_normal, upright_roi, params);
      out.push_back(needle);
    }
  }
  return out;
}

}  // namespace nerv::viz

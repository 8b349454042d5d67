#include "integral_normals.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "point_cloud.hpp"

namespace nerv::snv {

void IntegralNormalField::prepare(const cv::Mat& disparity, const StereoCamera& cam,
                                  const IntegralNormalParams& params, int row_begin, int row_end) {
  CV_Assert(disparity.type() == CV_32F);
  disparity_ = disparity;
  cam_ = cam;
  params_ = params;
  row0_ = std::clamp(row_begin, 0, disparity.rows);
  row1_ = std::clamp(row_end, row0_, disparity.rows);
  fb_ = static_cast<float>(cam.fx * cam.baseline_m);
  inv_fx_ = static_cast<float>(1.0 / cam.fx);
  inv_fy_ = static_cast<float>(1.0 / cam.fy);

  const int rows = row1_ - row0_, cols = disparity.cols;
  cv::Mat value(rows, cols, CV_32F);
  edge_.create(rows, cols, CV_8U);
  const float jump_px = params.depth_change_px, jump_rel = params.depth_change_rel;
  for (int v = row0_; v < row1_; ++v) {
    const float* d = disparity.ptr<float>(v);
    const float* below = v + 1 < disparity.rows ? disparity.ptr<float>(v + 1) : d;
    float* out = value.ptr<float>(v - row0_);
    uchar* e = edge_.ptr<uchar>(v - row0_);
    for (int u = 0; u < cols; ++u) {
      const float c = d[u];
      if (!validDisparity(c)) {
        out[u] = 0.0f;
        e[u] = 1;
        continue;
      }
      out[u] = params.smooth_disparity ? c : fb_ / c;
      // A jump to the right or below marks this pixel: any window spanning the
      // jump contains it.
      const float thr = std::max(jump_px, jump_rel * c);
      const float right = u + 1 < cols ? d[u + 1] : c;
      const bool jump = std::abs(right - c) > thr || std::abs(below[u] - c) > thr;
      e[u] = jump ? 1 : 0;
    }
  }
  cv::integral(value, value_integral_, CV_64F);
  cv::integral(edge_, edge_integral_, CV_32S);
}

double IntegralNormalField::boxSum(const cv::Mat& integral, int u, int v, int r) const {
  const int y0 = v - r - row0_, y1 = v + r + 1 - row0_, x0 = u - r, x1 = u + r + 1;
  const double* a = integral.ptr<double>(y0);
  const double* b = integral.ptr<double>(y1);
  return b[x1] - a[x1] - b[x0] + a[x0];
}

int IntegralNormalField::edgeCount(int u, int v, int r) const {
  const int y0 = v - r - row0_, y1 = v + r + 1 - row0_, x0 = u - r, x1 = u + r + 1;
  const int* a = edge_integral_.ptr<int>(y0);
  const int* b = edge_integral_.ptr<int>(y1);
  return b[x1] - a[x1] - b[x0] + a[x0];
}

float IntegralNormalField::smoothedDepth(int u, int v, int r) const {
  const double side = 2 * r + 1;
  const double mean = boxSum(value_integral_, u, v, r) / (side * side);
  if (params_.smooth_disparity) return mean > 0 ? static_cast<float>(fb_ / mean) : -1.0f;
  return static_cast<float>(mean);
}

int IntegralNormalField::depthRadius(int u, int v) const {
  if (u < 0 || u >= disparity_.cols || v < row0_ || v >= row1_) return 0;
  const float d = disparity_.at<float>(v, u);
  if (!validDisparity(d)) return 0;
  const float z = fb_ / d;
  int r = static_cast<int>((params_.window_base_px + params_.window_px_per_m * z) * 0.5f);
  r = std::min(r, params_.max_radius_px);
  // Every smoothing window reaches 2r from the centre and must stay in the band.
  const int border = std::min({u, disparity_.cols - 1 - u, v - row0_, row1_ - 1 - v});
  return std::max(0, std::min(r, border / 2));
}

int IntegralNormalField::adaptiveRadius(int u, int v) const {
  int r = depthRadius(u, v);
  while (r >= 1 && edgeCount(u, v, 2 * r) > 0) --r;
  return r;
}

bool IntegralNormalField::normalAt(int u, int v, int r, cv::Vec3f& n) const {
  const float zr = smoothedDepth(u + r, v, r), zl = smoothedDepth(u - r, v, r);
  const float zd = smoothedDepth(u, v + r, r), zu = smoothedDepth(u, v - r, r);
  if (!(zr > 0 && zl > 0 && zd > 0 && zu > 0)) return false;
  const float cx = static_cast<float>(cam_.cx), cy = static_cast<float>(cam_.cy);
  const float xr = (u + r - cx) * inv_fx_, xl = (u - r - cx) * inv_fx_, xc = (u - cx) * inv_fx_;
  const float yd = (v + r - cy) * inv_fy_, yu = (v - r - cy) * inv_fy_, yc = (v - cy) * inv_fy_;
  // Horizontal tangent h and vertical tangent t between the smoothed points.
  const float hx = xr * zr - xl * zl, hy = yc * (zr - zl), hz = zr - zl;
  const float tx = xc * (zd - zu), ty = yd * zd - yu * zu, tz = zd - zu;
  // N = t x h faces the camera for any visible surface.
  const float nx = ty * hz - tz * hy, ny = tz * hx - tx * hz, nz = tx * hy - ty * hx;
  const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (!(len > 0)) return false;
  const float inv = 1.0f / len;
  n = cv::Vec3f(nx * inv, ny * inv, nz * inv);
  return true;
}

cv::Mat IntegralNormalField::edgeDistance() const {
  cv::Mat inside = edge_ == 0;  // 255 off edges
  cv::Mat dist;
  cv::distanceTransform(inside, dist, cv::DIST_C, 3, CV_32F);
  return dist;
}

NormalMap computeNormalMap(const cv::Mat& disparity, const StereoCamera& cam,
                           const IntegralNormalParams& params, int interval_px) {
  CV_Assert(interval_px >= 1);
  NormalMap map;
  map.interval_px = interval_px;
  const int gw = (disparity.cols + interval_px - 1) / interval_px;
  const int gh = (disparity.rows + interval_px - 1) / interval_px;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  map.normals.create(gh, gw, CV_32FC3);
  if (disparity.empty()) return map;

  IntegralNormalField field;
  field.prepare(disparity, cam, params);
  // r = min(B, T) read from the edge integral (adaptiveRadius) rather than a
  // cv::distanceTransform: the same radius (see edgeDistance() and its test),
  // but O(1) per pixel without a full-frame transform.
  cv::parallel_for_(cv::Range(0, gh), [&](const cv::Range& range) {
    for (int j = range.start; j < range.end; ++j) {
      const int v = j * interval_px;
      cv::Vec3f* out = map.normals.ptr<cv::Vec3f>(j);
      for (int i = 0; i < gw; ++i) {
        const int u = i * interval_px;
        const int r = field.adaptiveRadius(u, v);
        cv::Vec3f n;
        if (r >= 1 && field.normalAt(u, v, r, n))
          out[i] = n;
        else
          out[i] = cv::Vec3f(nan, nan, nan);
      }
    }
  });
  return map;
}

}  // namespace nerv::snv

#include "naive_normals.hpp"

#include <cmath>
#include <limits>

#include "point_cloud.hpp"

namespace nerv::snv {
namespace {

cv::Vec3d point(const StereoCamera& cam, int u, int v, double z) {
  return {(u - cam.cx) / cam.fx * z, (v - cam.cy) / cam.fy * z, z};
}

bool unitNormal(const cv::Vec3d& vertical, const cv::Vec3d& horizontal, cv::Vec3f& n) {
  const cv::Vec3d c = vertical.cross(horizontal);
  const double len = cv::norm(c);
  if (!(len > 0)) return false;
  n = cv::Vec3f(static_cast<float>(c[0] / len), static_cast<float>(c[1] / len),
                static_cast<float>(c[2] / len));
  return true;
}

}  // namespace

NormalMap computeNaiveNormalMap(const cv::Mat& disparity, const StereoCamera& cam, int radius_px,
                                int interval_px) {
  CV_Assert(disparity.type() == CV_32F && radius_px >= 1 && interval_px >= 1);
  NormalMap map;
  map.interval_px = interval_px;
  const int gw = (disparity.cols + interval_px - 1) / interval_px;
  const int gh = (disparity.rows + interval_px - 1) / interval_px;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  map.normals.create(gh, gw, CV_32FC3);
  const double fb = cam.fx * cam.baseline_m;
  const int r = radius_px;
  for (int j = 0; j < gh; ++j) {
    const int v = j * interval_px;
    cv::Vec3f* out = map.normals.ptr<cv::Vec3f>(j);
    for (int i = 0; i < gw; ++i) {
      const int u = i * interval_px;
      out[i] = cv::Vec3f(nan, nan, nan);
      if (u < r || v < r || u + r >= disparity.cols || v + r >= disparity.rows) continue;
      const float dl = disparity.at<float>(v, u - r), dr = disparity.at<float>(v, u + r);
      const float du = disparity.at<float>(v - r, u), dd = disparity.at<float>(v + r, u);
      if (!validDisparity(dl) || !validDisparity(dr) || !validDisparity(du) || !validDisparity(dd))
        continue;
      const cv::Vec3d h = point(cam, u + r, v, fb / dr) - point(cam, u - r, v, fb / dl);
      const cv::Vec3d t = point(cam, u, v + r, fb / dd) - point(cam, u, v - r, fb / du);
      cv::Vec3f n;
      if (unitNormal(t, h, n)) out[i] = n;
    }
  }
  return map;
}

bool bruteForceSmoothedNormal(const cv::Mat& disparity, const StereoCamera& cam,
                              const IntegralNormalParams& params, int u, int v, int r,
                              cv::Vec3f& n) {
  const double fb = cam.fx * cam.baseline_m;
  auto smoothedDepth = [&](int cu, int cv_, double& z) {
    double sum = 0;
    for (int y = cv_ - r; y <= cv_ + r; ++y)
      for (int x = cu - r; x <= cu + r; ++x) {
        if (x < 0 || y < 0 || x >= disparity.cols || y >= disparity.rows) return false;
        const float d = disparity.at<float>(y, x);
        if (!validDisparity(d)) return false;
        sum += params.smooth_disparity ? d : fb / d;
      }
    const double mean = sum / ((2 * r + 1) * (2 * r + 1));
    z = params.smooth_disparity ? fb / mean : mean;
    return z > 0;
  };
  double zr, zl, zd, zu;
  if (!smoothedDepth(u + r, v, zr) || !smoothedDepth(u - r, v, zl) ||
      !smoothedDepth(u, v + r, zd) || !smoothedDepth(u, v - r, zu))
    return false;
  const cv::Vec3d h = point(cam, u + r, v, zr) - point(cam, u - r, v, zl);
  const cv::Vec3d t = point(cam, u, v + r, zd) - point(cam, u, v - r, zu);
  return unitNormal(t, h, n);
}

NormalMap computeNormalMapReference(const cv::Mat& disparity, const StereoCamera& cam,
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
  for (int j = 0; j < gh; ++j) {
    cv::Vec3f* out = map.normals.ptr<cv::Vec3f>(j);
    for (int i = 0; i < gw; ++i) {
      const int u = i * interval_px, v = j * interval_px;
      const int r = field.adaptiveRadius(u, v);
      cv::Vec3f n;
      out[i] = r >= 1 && field.normalAt(u, v, r, n) ? n : cv::Vec3f(nan, nan, nan);
    }
  }
  return map;
}

}  // namespace nerv::snv

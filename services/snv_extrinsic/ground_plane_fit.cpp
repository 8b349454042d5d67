#include "ground_plane_fit.hpp"

#include <algorithm>
#include <cmath>

#include "order_statistic.hpp"

namespace nerv::snv {
namespace {

// Weighted least squares of d on (u - cx, v - cy, 1); false when singular.
bool solveWeighted(const std::vector<PlanePoint>& pts, const std::vector<float>& w,
                   const StereoCamera& cam, double out[3]) {
  // Centre u, v on the principal point and scale to ~1 for conditioning.
  const double s = 1.0 / std::max(1.0, cam.fx);
  double m[6] = {0, 0, 0, 0, 0, 0}, r[3] = {0, 0, 0};  // symmetric 3x3: xx xy x1 yy y1 11
  for (size_t i = 0; i < pts.size(); ++i) {
    const double wi = w[i];
    if (wi <= 0) continue;
    const double x = (pts[i].u - cam.cx) * s, y = (pts[i].v - cam.cy) * s, d = pts[i].d;
    m[0] += wi * x * x; m[1] += wi * x * y; m[2] += wi * x;
    m[3] += wi * y * y; m[4] += wi * y;     m[5] += wi;
    r[0] += wi * x * d; r[1] += wi * y * d; r[2] += wi * d;
  }
  const cv::Matx33d A(m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5]);
  cv::Vec3d x;
  if (!cv::solve(A, cv::Vec3d(r[0], r[1], r[2]), x, cv::DECOMP_CHOLESKY)) return false;
  if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) return false;
  out[0] = x[0] * s;
  out[1] = x[1] * s;
  out[2] = x[2];
  return true;
}

}  // namespace

DisparityPlane fitDisparityPlane(const std::vector<PlanePoint>& pts, const StereoCamera& cam,
                                 const PlaneFitParams& params, const DisparityPlane* start) {
  DisparityPlane plane;
  if (pts.size() < 3) return plane;
  std::vector<float> w(pts.size(), 1.0f), res(pts.size()), absres;
  std::vector<uint32_t> select_scratch;
  double x[3];
  if (start && start->valid) {
    x[0] = start->a;
    x[1] = start->b;
    x[2] = start->c;
  } else if (!solveWeighted(pts, w, cam, x)) {
    return plane;
  }
  float sigma = 0;
  for (int it = 0; it < params.iterations; ++it) {
    for (size_t i = 0; i < pts.size(); ++i)
      res[i] = static_cast<float>(pts[i].d - (x[0] * (pts[i].u - cam.cx) + x[1] * (pts[i].v - cam.cy) + x[2])) /
               (params.relative ? pts[i].d : 1.0f);
    absres.resize(res.size());
    for (size_t i = 0; i < res.size(); ++i) absres[i] = std::abs(res[i]);
    // The value nth_element would leave at the middle (order_statistic.hpp).
    const float mad = kthSmallest(absres.data(), absres.size(), absres.size() / 2, select_scratch);
    sigma = std::max(params.relative ? params.min_sigma_rel : params.min_sigma_px, 1.4826f * mad);
    const float cut = params.tukey_k * sigma;
    for (size_t i = 0; i < res.size(); ++i) {
      const float t = res[i] / cut;
      w[i] = std::abs(t) < 1.0f ? (1 - t * t) * (1 - t * t) : 0.0f;
    }
    double nx[3];
    if (!solveWeighted(pts, w, cam, nx)) break;
    const bool small = std::abs(nx[0] - x[0]) * cam.width < 1e-4 &&
                       std::abs(nx[1] - x[1]) * cam.height < 1e-4 && std::abs(nx[2] - x[2]) < 1e-4;
    std::copy(nx, nx + 3, x);
    if (small) break;
  }
  plane.a = x[0];
  plane.b = x[1];
  plane.c = x[2];
  plane.sigma_px = sigma;
  plane.inliers = static_cast<int>(std::count_if(w.begin(), w.end(), [](float v) { return v > 0; }));
  plane.valid = true;
  return plane;
}

DisparityPlane planeFromNormal(const cv::Vec3f& n, float height_m, const StereoCamera& cam) {
  DisparityPlane p;
  if (!(height_m > 0)) return p;
  // (a fx, b fy, c) = -(fB / h) n for the up normal n.
  const double s = -cam.fx * cam.baseline_m / height_m;
  p.a = s * n[0] / cam.fx;
  p.b = s * n[1] / cam.fy;
  p.c = s * n[2];
  p.valid = true;
  return p;
}

cv::Vec3f planeNormal(const DisparityPlane& p, const StereoCamera& cam) {
  const cv::Vec3d g(p.a * cam.fx, p.b * cam.fy, p.c);
  const double len = cv::norm(g);
  if (!(len > 0)) return cv::Vec3f(0, -1, 0);
  return cv::Vec3f(static_cast<float>(-g[0] / len), static_cast<float>(-g[1] / len),
                   static_cast<float>(-g[2] / len));
}

float planeHeightM(const DisparityPlane& p, const StereoCamera& cam) {
  const double len = cv::norm(cv::Vec3d(p.a * cam.fx, p.b * cam.fy, p.c));
  return len > 0 ? static_cast<float>(cam.fx * cam.baseline_m / len) : 0.0f;
}

}  // namespace nerv::snv

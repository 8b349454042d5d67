#include "ground_samples.hpp"

#include <algorithm>
#include <cmath>

#include "point_cloud.hpp"

namespace nerv::snv {
namespace {

bool usableModel(const GroundModel& m) {
  return m.valid && m.vd_slope > 0 && std::isfinite(m.vd_slope) && std::isfinite(m.vd_intercept);
}

}  // namespace

cv::Range groundRows(const StereoCamera& cam, const GroundModel& model,
                     const GroundSampleParams& params) {
  int first;
  if (usableModel(model)) {
    // Row where the model's ground is max_depth_m away.
    const double d_far = cam.fx * cam.baseline_m / params.max_depth_m;
    first = static_cast<int>(std::floor((d_far - model.vd_intercept) / model.vd_slope));
  } else {
    first = static_cast<int>(std::ceil(cam.cy)) + params.lower_margin_px;
  }
  first = std::clamp(first, 0, cam.height);
  return cv::Range(first, cam.height);
}

bool isGroundCandidate(int v, float d, const StereoCamera& cam, const GroundModel& model,
                       const GroundSampleParams& params) {
  if (!validDisparity(d)) return false;
  const double z = cam.fx * cam.baseline_m / d;
  if (z > params.max_depth_m || z < params.min_depth_m) return false;
  if (!usableModel(model)) return v > cam.cy + params.lower_margin_px;
  const float dg = model.groundDisparity(static_cast<float>(v));
  if (!(dg > 0)) return false;
  return std::abs(d - dg) <= std::max(params.disparity_tol_px, params.disparity_tol_rel * dg);
}

std::vector<GroundSample> selectGroundSamples(const IntegralNormalField& field,
                                              const cv::Mat& disparity, const StereoCamera& cam,
                                              const GroundModel& model,
                                              const GroundSampleParams& params, cv::Range rows,
                                              int interval_px) {
  std::vector<GroundSample> out;
  if (field.empty() || rows.empty()) return out;
  const float min_up = static_cast<float>(std::cos(params.prior_cone_deg * CV_PI / 180.0));
  const float fb = static_cast<float>(cam.fx * cam.baseline_m);
  const int v0 = (std::max(rows.start, field.rowBegin()) + interval_px - 1) / interval_px * interval_px;
  const int v1 = std::min(rows.end, field.rowEnd());
  for (int v = v0; v < v1; v += interval_px) {
    const float* d = disparity.ptr<float>(v);
    for (int u = 0; u < disparity.cols; u += interval_px) {
      if (!isGroundCandidate(v, d[u], cam, model, params)) continue;
      const int r = field.adaptiveRadius(u, v);
      cv::Vec3f n;
      if (r < 1 || !field.normalAt(u, v, r, n) || -n[1] < min_up) continue;
      const float z = fb / d[u];
      out.push_back({u, v, n,
                     cv::Vec3f(static_cast<float>((u - cam.cx) / cam.fx) * z,
                               static_cast<float>((v - cam.cy) / cam.fy) * z, z)});
    }
  }
  return out;
}

}  // namespace nerv::snv

#include "pitch_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nerv::viz {

PitchDistribution computePitchDistribution(const cv::Mat& disparity, const StereoCamera& cam,
                                           const ground_model_t& ground, const PitchDistributionParams& params) {
  PitchDistribution out;
  out.bin_deg = params.bin_deg;
  out.mode_deg = out.mean_deg = std::numeric_limits<float>::quiet_NaN();
  if (!ground.valid || !std::isfinite(ground.vd_slope) || !std::isfinite(ground.vd_intercept) || disparity.empty())
    return out;
  NeedleParams np;
  np.interval_px = params.interval_px;
  const auto needles = computeNeedles(disparity, cam, {0, -1, 0}, cv::Mat(), np);
  const float cos_cone = std::cos(params.prior_cone_deg * float(CV_PI) / 180);
  double sum = 0;
  for (const auto& n : needles) {
    const float dg = ground.vd_slope * n.v + ground.vd_intercept;
    if (!(dg > 0)) continue;
    const float d = disparity.at<float>(n.v, n.u);
    if (std::abs(d - dg) > std::max(params.disparity_tol_px, params.disparity_tol_rel * dg)) continue;
    if (n.p[2] < params.min_depth_m || n.p[2] > params.max_depth_m) continue;
    if (-n.n[1] < cos_cone) continue;
    const float pitch = std::atan2(-n.n[2], -n.n[1]) * float(180 / CV_PI);
    out.pitch_deg.push_back(pitch);
    sum += pitch;
  }
  if (out.pitch_deg.empty()) return out;
  const auto [lo, hi] = std::minmax_element(out.pitch_deg.begin(), out.pitch_deg.end());
  out.origin_deg = std::floor(*lo / params.bin_deg) * params.bin_deg;
  const int bins = static_cast<int>((*hi - out.origin_deg) / params.bin_deg) + 1;
  out.counts.assign(std::min(bins, 100000), 0.0);
  for (float p : out.pitch_deg) {
    const int k = std::clamp(static_cast<int>((p - out.origin_deg) / params.bin_deg), 0, int(out.counts.size()) - 1);
    out.counts[k] += 1;
  }
  const size_t mode = std::max_element(out.counts.begin(), out.counts.end()) - out.counts.begin();
  out.mode_deg = out.origin_deg + (mode + 0.5f) * params.bin_deg;
  out.mean_deg = static_cast<float>(sum / out.pitch_deg.size());
  return out;
}

}  // namespace nerv::viz

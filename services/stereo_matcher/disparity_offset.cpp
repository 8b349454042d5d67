#include "disparity_offset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "robust_fit.hpp"

namespace nerv::stereo {

DisparityOffset measureDisparityOffset(const MotionTracks& tracks, double fx, double cx, double cy,
                                       const DisparityOffsetParams& p) {
  DisparityOffset out;
  const MatchedPoints& m = tracks.matched;
  if (!(fx > 0) || !std::isfinite(cx) || !std::isfinite(cy) || tracks.before.size() != m.left.size() ||
      tracks.tracked.size() != m.left.size())
    return out;
  std::vector<FitRow<6>> x;
  std::vector<double> y, ud;
  for (size_t i = 0; i < m.left.size(); ++i) {
    if (!tracks.tracked[i]) continue;
    const double ub = tracks.before[i].x - cx, vb = tracks.before[i].y - cy, d = m.disparity[i];
    x.push_back(stepFlowRow(ub, vb, d, fx));
    y.push_back(m.left[i].x - tracks.before[i].x);
    ud.push_back(std::abs(ub * d));
  }
  out.points = static_cast<int>(y.size());
  if (out.points < p.min_points) return out;
  FitRow<6> c;
  FitCovariance<6> cov;
  if (!huberFit<6>(x, y, c, &cov)) return out;
  out.k = c[4];
  out.motion_px = stepAtPoints(out.k, std::move(ud));
  if (!(out.k > 0) || out.motion_px < p.min_motion_px) return out;
  // e = -c5 / c4: first-order error propagation.
  const double e = -c[5] / c[4];
  const double var = (cov(5, 5) + e * e * cov(4, 4) + 2 * e * cov(4, 5)) / (c[4] * c[4]);
  out.offset_px = static_cast<float>(e);
  out.sigma_px = static_cast<float>(std::sqrt(std::max(0.0, var)));
  out.valid = std::isfinite(out.offset_px) && std::isfinite(out.sigma_px) && out.sigma_px <= p.max_sigma_px;
  return out;
}

std::string describeDisparityOffset(const MedianVerdict& offsets, double applied) {
  const float m = static_cast<float>(offsets.median() + applied);
  char line[200];
  std::snprintf(line, sizeof line,
                "the disparity reads %.2f px %s than the forward motion says (median of the last %d checks while moving, "
                "%.2f to %.2f px)",
                std::abs(m), m >= 0 ? "more" : "less", offsets.samples(), offsets.lowest() + applied,
                offsets.highest() + applied);
  return line;
}

}  // namespace nerv::stereo

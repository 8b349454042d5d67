#include "roi_normal_stats.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::snv {
namespace {

constexpr double kDeg = CV_PI / 180.0;

float median(std::vector<float>& v) {
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

NormalStats computeRoiStats(int roi_id, int num_samples, const std::vector<LocalNormal>& normals,
                            const cv::Vec3f& ground_normal,
                            const RoiStatsParams& params) {
  NormalStats s;
  s.roi_id = roi_id;
  s.num_samples = std::max(0, num_samples);
  s.num_normals = static_cast<int>(normals.size());
  if (s.num_samples == 0 || s.num_normals == 0) return s;
  s.density = static_cast<float>(s.num_normals) / static_cast<float>(s.num_samples);

  const cv::Vec3f g = cv::normalize(ground_normal);
  const float cos_ground = static_cast<float>(std::cos(params.ground_tolerance_deg * kDeg));
  const float sin_upright = static_cast<float>(std::sin(params.upright_tolerance_deg * kDeg));
  const float cos_facing = static_cast<float>(std::cos(params.facing_cone_deg * kDeg));
  int ground = 0, upright = 0, facing = 0, facing_upright = 0;
  std::vector<float> nx, ny, nz;
  nx.reserve(normals.size());
  ny.reserve(normals.size());
  nz.reserve(normals.size());
  for (const LocalNormal& ln : normals) {
    const cv::Vec3f& n = ln.n;
    nx.push_back(n[0]);
    ny.push_back(n[1]);
    nz.push_back(n[2]);
    const float along_g = n.dot(g);
    if (along_g >= cos_ground) {
      ++ground;
      continue;
    }
    const bool is_upright = std::abs(along_g) <= sin_upright;  // |90 deg - tilt| <= tolerance
    if (-n[2] >= cos_facing) {
      ++facing;
      if (is_upright) ++facing_upright;
    } else if (is_upright) {
      ++upright;
    }
  }
  const float total = static_cast<float>(s.num_normals);
  const bool upright_consistent = upright >= params.upright_consistency_fraction * total;
  s.ground_fraction = ground / total;
  s.object_fraction = (upright + (upright_consistent ? facing_upright : 0)) / total;
  s.error_fraction = upright_consistent ? 0.0f : facing / total;

  // Representative normal: component-wise median, normalised (robust to the
  // mix of faces a box shows).
  cv::Vec3f rep(median(nx), median(ny), median(nz));
  const float len = static_cast<float>(cv::norm(rep));
  if (len > 1e-6f) {
    rep /= len;
    s.normal[0] = rep[0];
    s.normal[1] = rep[1];
    s.normal[2] = rep[2];
    // Elevation from the image plane (90 deg: facing the camera) and azimuth
    // about the vertical (0: facing the camera, positive: turned to +x).
    s.pitch_deg = static_cast<float>(std::asin(std::clamp(-rep[2], -1.0f, 1.0f)) / kDeg);
    s.yaw_deg = static_cast<float>(std::atan2(rep[0], -rep[2]) / kDeg);
    s.tilt_from_ground_deg =
        static_cast<float>(std::acos(std::clamp(rep.dot(g), -1.0f, 1.0f)) / kDeg);
  }
  return s;
}

}  // namespace nerv::snv

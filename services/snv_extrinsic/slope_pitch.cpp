#include "slope_pitch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "adaptive_mean_shift.hpp"
#include "super_snv.hpp"

namespace nerv::snv {
namespace {

constexpr double kDeg = CV_PI / 180.0;

// Up normal of the road for a camera pitch/roll (double precision twin of
// normalFromPitchRoll in super_snv.hpp).
cv::Vec3d upNormal(double pitch_deg, double roll_deg) {
  const double tp = std::tan(pitch_deg * kDeg), tr = std::tan(roll_deg * kDeg);
  return cv::Vec3d(-tr, -1.0, -tp) / std::sqrt(tp * tp + tr * tr + 1.0);
}

cv::Vec3d ray(const StereoCamera& cam, double u, double v) {
  return cv::Vec3d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
}

float median(std::vector<float>& v) {
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

float normalisedVerticalSlope(const cv::Vec3f& n, float u, float v, const StereoCamera& cam) {
  const double s = cv::Vec3d(n[0], n[1], n[2]).dot(ray(cam, u, v));
  if (s == 0) return std::numeric_limits<float>::quiet_NaN();
  return static_cast<float>(n[1] / (cam.fy * s));
}

double roadNormalisedSlope(float pitch_deg, float roll_deg, double u, double v, const StereoCamera& cam) {
  const cv::Vec3d n = upNormal(pitch_deg, roll_deg);
  return n[1] / (cam.fy * n.dot(ray(cam, u, v)));
}

void linearisedPitchesDeg(const std::vector<SlopeSample>& samples, const StereoCamera& cam,
                          float roll_deg, float pitch_deg, std::vector<float>& out) {
  // d n / d theta per degree, central difference (n is smooth in theta).
  const double h = 1e-3;
  const cv::Vec3d n = upNormal(pitch_deg, roll_deg);
  const cv::Vec3d dn = (upNormal(pitch_deg + h, roll_deg) - upNormal(pitch_deg - h, roll_deg)) / (2 * h);
  const double ax = n[0] / cam.fx, ay = n[1] / cam.fy, az = n[2] - n[0] * cam.cx / cam.fx - n[1] * cam.cy / cam.fy;
  const double bx = dn[0] / cam.fx, by = dn[1] / cam.fy, bz = dn[2] - dn[0] * cam.cx / cam.fx - dn[1] * cam.cy / cam.fy;
  out.clear();
  out.reserve(samples.size());
  for (const SlopeSample& s : samples) {
    // n . ray and its derivative, affine in (u, v).
    const double nr = ax * s.u + ay * s.v + az, dnr = bx * s.u + by * s.v + bz;
    if (!(std::abs(nr) > 1e-9) || !std::isfinite(s.beta)) continue;
    const double beta0 = n[1] / (cam.fy * nr);
    const double g = (dn[1] * nr - n[1] * dnr) / (cam.fy * nr * nr);  // d beta / d theta [1/px/deg]
    if (!(std::abs(g) > 1e-12)) continue;
    out.push_back(static_cast<float>(pitch_deg + (s.beta - beta0) / g));
  }
}

SlopePitchResult fitSlopePitch(const std::vector<SlopeSample>& samples, const StereoCamera& cam,
                               float roll_deg, float start_pitch_deg, const SlopePitchParams& p) {
  SlopePitchResult res;
  if (samples.size() < 3) return res;
  double pitch = start_pitch_deg;
  std::vector<float> theta, dev;
  for (res.iterations = 1; res.iterations <= p.iterations; ++res.iterations) {
    linearisedPitchesDeg(samples, cam, roll_deg, static_cast<float>(pitch), theta);
    if (theta.size() < 3) return res;
    double next = pitch;
    if (p.mean_shift) {
      sortAngles(theta);
      const MeanShiftResult ms = adaptiveMeanShift(theta, static_cast<float>(pitch), p.fraction, p.stop_deg * 0.1f);
      next = ms.estimate;
      res.inliers = ms.inliers;
      res.sigma_deg = ms.radius;
    } else {
      dev.resize(theta.size());
      for (size_t i = 0; i < theta.size(); ++i) dev[i] = std::abs(theta[i] - static_cast<float>(pitch));
      const float sigma = std::max(p.min_sigma_deg, 1.4826f * median(dev));
      const double cut = p.tukey_k * sigma;
      double sw = 0, swe = 0;
      int inl = 0;
      for (const float t : theta) {
        const double e = t - pitch, r = e / cut;
        if (std::abs(r) >= 1) continue;
        const double w = (1 - r * r) * (1 - r * r);
        sw += w;
        swe += w * e;
        ++inl;
      }
      if (!(sw > 0)) return res;
      next = pitch + swe / sw;
      res.inliers = inl;
      res.sigma_deg = sigma;
    }
    const double moved = std::abs(next - pitch);
    pitch = next;
    if (moved < p.stop_deg) break;
  }
  res.iterations = std::min(res.iterations, p.iterations);
  res.pitch_deg = static_cast<float>(pitch);
  res.valid = std::isfinite(res.pitch_deg);
  return res;
}

}  // namespace nerv::snv

#include "ground_geometry.hpp"

#include <cmath>

namespace nerv::stixel {

namespace {
constexpr double kDegPerRad = 180.0 / M_PI;
}

LinePose poseFromGroundLine(float slope, float intercept, const StereoCamera& cam) {
  LinePose p;
  const double a = slope, b = intercept;
  const double tilt = std::atan((a * cam.cy + b) / (cam.fy * a));
  p.pitch_deg = static_cast<float>(tilt * kDegPerRad);
  p.height_m = static_cast<float>(cam.fx * cam.baseline_m * std::cos(tilt) / (cam.fy * a));
  p.horizon_row = static_cast<float>(-b / a);
  return p;
}

void groundLineFromPose(float pitch_deg, float height_m, const StereoCamera& cam,
                        float& slope, float& intercept) {
  const double t = pitch_deg / kDegPerRad;
  const double k = cam.fx * cam.baseline_m / height_m;
  const double a = k * std::cos(t) / cam.fy;
  slope = static_cast<float>(a);
  intercept = static_cast<float>(k * std::sin(t) - a * cam.cy);
}

GroundModel groundModelFromLine(float slope, float intercept, const StereoCamera& cam,
                                const char* source) {
  GroundModel g;
  const LinePose p = poseFromGroundLine(slope, intercept, cam);
  g.valid = true;
  g.source = source;
  g.vd_slope = slope;
  g.vd_intercept = intercept;
  g.horizon_row = p.horizon_row;
  g.pitch_deg = p.pitch_deg;
  g.height_m = p.height_m;
  return g;
}

}  // namespace nerv::stixel

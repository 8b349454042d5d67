#include "sky.hpp"

#include <cmath>

#include "noise.hpp"

namespace nerv::synth {

cv::Vec3f skyColour(const World& w, const Vec3& dir, float footprint_rad) {
  const Vec3 d = dir.normalized();
  const float up = static_cast<float>(std::max(d.y(), 0.0));
  const float k = std::sqrt(clamp01(up * 2.5f));
  const cv::Vec3f horizon(215, 208, 200), zenith(205, 155, 105);
  cv::Vec3f c = horizon * (1 - k) + zenith * k;
  if (up > 0.01f) {
    // Clouds on a plane 1 km up; footprint grows with the slant distance.
    const float dist = 1000.0f / up;
    const float cx = static_cast<float>(d.x() * dist), cz = static_cast<float>(d.z() * dist);
    const float fp = footprint_rad * dist / up;
    const float cloud = smoothstep(0.0f, 0.5f, fbm(cx, cz, w.seed + 77u, 0.0025f, 6, fp * 0.5f, 0.55f));
    c = c * (1 - 0.8f * cloud) + cv::Vec3f(235, 235, 235) * (0.8f * cloud);
  }
  const float cos_sun = static_cast<float>(d.dot(w.sun_dir));
  if (w.traps.overexposed_sky) {
    // Low sun ahead: a wide glare that clips the sensor.
    const float glare = std::exp((cos_sun - 1.0f) * 9.0f);
    c += cv::Vec3f(1, 1, 1) * (320.0f * glare);
  } else {
    c += cv::Vec3f(1, 1, 1) * (40.0f * std::pow(std::max(cos_sun, 0.0f), 16.0f));
  }
  return c;
}

}  // namespace nerv::synth

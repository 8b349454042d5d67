#include "synthetic_road_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nerv::stixel {

FaceColumns paintFace(cv::Mat& disp, const RoadScene& scene, const StereoCamera& cam, float z_m, double x_left_m,
                      double x_right_m, double bottom_m, double top_m) {
  const double foot = footRow(scene, cam, z_m), px_per_m = cam.fx / z_m;
  const int u0 = static_cast<int>(std::lround(cam.cx + x_left_m * px_per_m));
  const int u1 = static_cast<int>(std::lround(cam.cx + x_right_m * px_per_m));
  disp(cv::Range(std::max(0, static_cast<int>(std::lround(foot - top_m * px_per_m))),
                 static_cast<int>(std::lround(foot - bottom_m * px_per_m))),
       cv::Range(u0, u1))
      .setTo(static_cast<float>(cam.fx * cam.baseline_m / z_m));
  return {u0, u1};
}

StereoCamera kittiLikeCamera() {
  StereoCamera c;
  c.width = 1242;
  c.height = 375;
  c.fx = c.fy = 721.5377;
  c.cx = 609.5593;
  c.cy = 172.854;
  c.baseline_m = 0.5327;
  return c;
}

// Level frame: the camera frame pitched back, x right, y down, z forward.
// A camera ray r (z component 1) at scale t has level coordinates
//   y_l = t*(r_y*cos + sin),  z_l = t*(cos - r_y*sin),  x_l = t*r_x,
// and t is also its camera depth Z, so the disparity is fx*B/t.
cv::Mat renderDisparity(const RoadScene& s, const StereoCamera& cam) {
  cv::Mat disp(cam.height, cam.width, CV_32F, cv::Scalar(0));
  const double th = s.pitch_deg * M_PI / 180.0, c = std::cos(th), sn = std::sin(th);
  for (int v = 0; v < cam.height; ++v) {
    const double ry = (v - cam.cy) / cam.fy;
    const double down = ry * c + sn, fwd = c - ry * sn;
    for (int u = 0; u < cam.width; ++u) {
      const double rx = (u - cam.cx) / cam.fx;
      double t = std::numeric_limits<double>::infinity();
      if (s.has_road && down > 1e-9) t = s.camera_height_m / down;
      for (const SceneBox& b : s.boxes) {
        if (fwd <= 1e-9) continue;
        const double tb = b.z_m / fwd;
        const double x = tb * rx, y = tb * down;
        if (tb < t && x >= b.x_left_m && x <= b.x_right_m && y <= s.camera_height_m &&
            y >= s.camera_height_m - b.height_m)
          t = tb;
      }
      if (std::isfinite(t)) disp.at<float>(v, u) = static_cast<float>(cam.fx * cam.baseline_m / t);
    }
  }
  return disp;
}

double footRow(const RoadScene& s, const StereoCamera& cam, double z_m) {
  // Level point (0, h, z) in camera coordinates: y = h*cos - z*sin, z_c = h*sin + z*cos.
  const double th = s.pitch_deg * M_PI / 180.0;
  const double y = s.camera_height_m * std::cos(th) - z_m * std::sin(th);
  const double zc = s.camera_height_m * std::sin(th) + z_m * std::cos(th);
  return cam.cy + cam.fy * y / zc;
}

}  // namespace nerv::stixel

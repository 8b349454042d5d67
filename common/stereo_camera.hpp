// Rectified pinhole stereo camera and the disparity <-> 3D relations every stage uses.
#pragma once

#include <cmath>
#include <string>

namespace nerv {

// Left (reference) camera frame: x right, y down, z forward, metres.
struct Point3 {
  double x = 0, y = 0, z = 0;
};

struct StereoCamera {
  int width = 0;            // image width [px]
  int height = 0;           // image height [px]
  double fx = 0, fy = 0;    // focal lengths [px]
  double cx = 0, cy = 0;    // principal point [px]
  double baseline_m = 0;    // optical centre distance [m]

  // Empty string when usable (positive size, focal lengths 1..1e6 px, principal
  // point within one image size of the image, baseline (0, 100] m), otherwise
  // one line naming the first problem.
  std::string problem() const;

  // Z = fx*B/d, X = (u-cx)*B/d, Y = (v-cy)*B/d * fx/fy (fy = fx for KITTI). d must be > 0.
  Point3 toPoint(double u, double v, double d) const {
    const double k = baseline_m / d;
    return {(u - cx) * k, (v - cy) * k * fx / fy, fx * k};
  }
  double depthFromDisparity(double d) const { return fx * baseline_m / d; }
  double disparityFromDepth(double z_m) const { return fx * baseline_m / z_m; }
  // Projection of a 3D point into the left image; returns false behind the camera.
  bool project(const Point3& p, double& u, double& v) const {
    if (!(p.z > 0)) return false;
    u = fx * p.x / p.z + cx;
    v = fy * p.y / p.z + cy;
    return true;
  }
};

}  // namespace nerv

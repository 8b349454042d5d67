// The v-disparity ground line and the camera pose over a flat road are two
// views of one thing; this file converts between them.
//
// Camera pitched down by theta at height h over a plane road (x right, y down,
// z forward). A camera point (X, Y, Z) lies Y*cos(theta) + Z*sin(theta) below the
// optical centre in the level frame, so the road is Y*cos + Z*sin = h. With
// Y = (v - cy)*Z/fy and Z = fx*B/d this gives the v-disparity line
//     d(v) = (fx*B/h) * ((v - cy)/fy * cos(theta) + sin(theta)) = a*v + b,
//     a = fx*B*cos(theta)/(fy*h),   b = (fx*B/h)*sin(theta) - a*cy,
// and back: tan(theta) = (a*cy + b)/(fy*a), h = fx*B*cos(theta)/(fy*a)
// (fy = fx: tilt = atan((a*cy + b)/(fx*a)), h = B*cos(tilt)/a; Labayrade et al.
// 2002 "Real time obstacle detection in stereovision on non flat road geometry").
#pragma once

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct LinePose {
  float pitch_deg = 0;
  float height_m = 0;
  float horizon_row = 0;
};

// Pose implied by the ground line d = slope*v + intercept; slope must be > 0.
LinePose poseFromGroundLine(float slope, float intercept, const StereoCamera& cam);

// Ground line of a camera at height_m pitched by pitch_deg (roll is ignored:
// the v-disparity of a rolled road is no longer a line).
void groundLineFromPose(float pitch_deg, float height_m, const StereoCamera& cam,
                        float& slope, float& intercept);

// Complete ground model (horizon, pose) from a line; `source` names its origin.
GroundModel groundModelFromLine(float slope, float intercept, const StereoCamera& cam,
                                const char* source);

// Height of the point seen at row v with disparity d over the road [m].
// The level-frame depth below the camera is h*d_g(v)/d (d_g = ground disparity of
// the row), hence height = h*(d - d_g(v))/d.
inline float heightAboveGround(const GroundModel& g, float v, float d) {
  return g.height_m * (d - g.groundDisparity(v)) / d;
}

}  // namespace nerv::stixel

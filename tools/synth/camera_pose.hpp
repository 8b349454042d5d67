// Pose of the stereo rig in the world for each frame: the vehicle drives along
// the road; the camera's pitch, roll and height are relative to the road plane
// under it (pitch positive = looks down, roll positive = clockwise seen from
// behind), with optional oscillation (braking / pitching) and bumps.
#pragma once

#include "primitives.hpp"
#include "scene.hpp"
#include "world.hpp"

namespace nerv::synth {

struct CameraPose {
  double time_s = 0;
  Vec3 centre = Vec3::Zero();  // left camera optical centre (world)
  Vec3 right = Vec3::UnitX(), down = -Vec3::UnitY(), forward = Vec3::UnitZ();  // camera axes in world
  double pitch_deg = 0, roll_deg = 0, height_m = 0;  // against the road under the camera

  Vec3 toCamera(const Vec3& p_world) const {
    const Vec3 q = p_world - centre;
    return Vec3(right.dot(q), down.dot(q), forward.dot(q));
  }
  Vec3 rightCentre(double baseline_m) const { return centre + right * baseline_m; }
};

// Pitch, roll and height of the rig at time t (before placing it on the road).
void rigState(const CameraRig& rig, double t_s, double& pitch_deg, double& roll_deg, double& height_m);

CameraPose cameraPose(const CameraRig& rig, const World& world, int frame);
// The same at any time t [s] (frame / fps for a frame), e.g. between two frames.
CameraPose cameraPoseAt(const CameraRig& rig, const World& world, double t);

}  // namespace nerv::synth

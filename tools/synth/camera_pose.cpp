#include "camera_pose.hpp"

#include <cmath>

namespace nerv::synth {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
}  // namespace

void rigState(const CameraRig& rig, double t, double& pitch_deg, double& roll_deg, double& height_m) {
  const double phase = 2 * kPi * t / rig.pitch_period_s;
  pitch_deg = rig.pitch_deg + rig.pitch_amplitude_deg * std::sin(phase);
  // The body dives (lower camera) while pitching down.
  height_m = rig.height_m - rig.height_amplitude_m * std::sin(phase);
  roll_deg = rig.roll_deg + rig.roll_amplitude_deg * std::sin(2 * kPi * t / rig.roll_period_s);
  if (rig.bump_interval_s > 0 && rig.bump_pitch_deg != 0) {
    // A bump: damped oscillation of the suspension (1.5 Hz, decay 0.35 s).
    const double since = std::fmod(t, rig.bump_interval_s);
    pitch_deg += rig.bump_pitch_deg * std::exp(-since / 0.35) * std::sin(2 * kPi * 1.5 * since);
  }
}

CameraPose cameraPose(const CameraRig& rig, const World& world, int frame) {
  return cameraPoseAt(rig, world, frame / rig.fps);
}

CameraPose cameraPoseAt(const CameraRig& rig, const World& world, double t) {
  CameraPose pose;
  pose.time_s = t;
  rigState(rig, pose.time_s, pose.pitch_deg, pose.roll_deg, pose.height_m);
  const double z = rig.speed_mps * pose.time_s;  // distance along the road (flat part: exact)
  const Vec3 n = world.roadNormal(z);
  const Vec3 along = Vec3::UnitX().cross(n).normalized();  // road tangent, pointing forward
  const Vec3 r0 = Vec3::UnitX(), d0 = -n, f0 = along;
  const double th = pose.pitch_deg * kDeg, ph = pose.roll_deg * kDeg;
  // Pitch about the right axis: forward tilts towards down.
  const Vec3 f1 = f0 * std::cos(th) + d0 * std::sin(th);
  const Vec3 d1 = d0 * std::cos(th) - f0 * std::sin(th);
  // Roll about the forward axis: clockwise seen from behind, right tilts down.
  pose.right = r0 * std::cos(ph) + d1 * std::sin(ph);
  pose.down = d1 * std::cos(ph) - r0 * std::sin(ph);
  pose.forward = f1;
  const Vec3 foot(rig.lateral_m, world.profile(z), z);
  pose.centre = foot + n * pose.height_m;
  return pose;
}

}  // namespace nerv::synth

// The renderable world at one instant: the analytic ground (road, curbs,
// sidewalks, terrain), solids made of primitives, wet patches and the sky.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "materials.hpp"
#include "primitives.hpp"
#include "scene.hpp"

namespace nerv::synth {

struct Part {
  Shape shape = Shape::Box;
  Vec3 c = Vec3::Zero();  // centre, object-local
  Vec3 e = Vec3::Zero();  // extents (see Shape)
  Surface surface;
  bool trap = false;      // part of a disparity trap (textureless panel, railing)
};

struct Solid {
  std::string type;       // KITTI label type ("Car", "Pole", ...), "DontCare" or "" (unlabelled)
  double height_m = 0, width_m = 0, length_m = 0;  // label 3D size; local bounds
  Vec3 base0 = Vec3::Zero();     // world position of the bottom centre at t = 0
  double yaw = 0;                // heading in world: (sin yaw, 0, cos yaw)
  double speed_mps = 0;          // along the heading
  bool casts_shadow = false;     // darkens the ground under it (contact shadow)
  uint32_t seed = 0;             // texture seed
  std::vector<Part> parts;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // local bounding box of all parts

  // Pose at the current time (World::setTime).
  Vec3 base = Vec3::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // columns: local x, y, z in world
  Vec3 world_lo = Vec3::Zero(), world_hi = Vec3::Zero();  // world bounding box (cheap ray rejection)

  void computeBounds();
  Vec3 toLocal(const Vec3& p_world) const { return R.transpose() * (p_world - base); }
  Vec3 dirToLocal(const Vec3& d_world) const { return R.transpose() * d_world; }
};

struct WetArea {  // ellipse on the road, world x/z
  double x, z, half_width, half_length;
};

struct World {
  RoadSpec road;
  TrapSpec traps;
  uint32_t seed = 1;
  std::vector<Solid> solids;
  std::vector<WetArea> wet;
  Vec3 sun_dir = Vec3(-0.35, 0.75, 0.55).normalized();  // towards the sun

  // Road surface height at z (the piecewise-linear profile).
  double profile(double z) const;
  // Ground height at (x, z): road, or road + curb outside the carriageway.
  double groundHeight(double x, double z) const;
  // Unit normal of the road surface at z.
  Vec3 roadNormal(double z) const;
  // Moves the dynamic solids to time t [s].
  void setTime(double t_s);
};

}  // namespace nerv::synth

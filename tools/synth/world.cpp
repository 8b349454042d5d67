#include "world.hpp"

#include <cmath>

namespace nerv::synth {

void Solid::computeBounds() {
  lo = Vec3::Constant(1e30);
  hi = Vec3::Constant(-1e30);
  for (const Part& p : parts) {
    Vec3 e = p.e;  // a box's half extents; set before the switch, so GCC 12 sees it set on every path
    switch (p.shape) {
      case Shape::Box: break;
      case Shape::CylinderY: e = Vec3(p.e.x(), p.e.y(), p.e.x()); break;
      case Shape::CylinderX: e = Vec3(p.e.x(), p.e.y(), p.e.y()); break;
      case Shape::Sphere: e = Vec3::Constant(p.e.x()); break;
    }
    lo = lo.cwiseMin(p.c - e);
    hi = hi.cwiseMax(p.c + e);
  }
}

double World::profile(double z) const {
  return z <= road.slope_start_m ? 0.0 : road.grade_percent * 0.01 * (z - road.slope_start_m);
}

double World::groundHeight(double x, double z) const {
  const bool on_road = x >= road.roadLeft() && x <= road.roadRight();
  return profile(z) + (on_road ? 0.0 : road.curb_height_m);
}

Vec3 World::roadNormal(double z) const {
  const double g = z <= road.slope_start_m ? 0.0 : road.grade_percent * 0.01;
  return Vec3(0, 1, -g).normalized();
}

void World::setTime(double t_s) {
  for (Solid& s : solids) {
    const Vec3 heading(std::sin(s.yaw), 0, std::cos(s.yaw));
    const Vec3 right(std::cos(s.yaw), 0, -std::sin(s.yaw));
    s.R.col(0) = right;
    s.R.col(1) = Vec3(0, 1, 0);
    s.R.col(2) = heading;
    s.base = s.base0 + heading * (s.speed_mps * t_s);
    if (s.speed_mps != 0) s.base.y() = groundHeight(s.base.x(), s.base.z()) + (s.base0.y() -
                                        groundHeight(s.base0.x(), s.base0.z()));
    s.world_lo = Vec3::Constant(1e30);
    s.world_hi = Vec3::Constant(-1e30);
    for (int c = 0; c < 8; ++c) {
      const Vec3 p = s.base + s.R * Vec3(c & 1 ? s.hi.x() : s.lo.x(), c & 2 ? s.hi.y() : s.lo.y(),
                                         c & 4 ? s.hi.z() : s.lo.z());
      s.world_lo = s.world_lo.cwiseMin(p);
      s.world_hi = s.world_hi.cwiseMax(p);
    }
  }
}

}  // namespace nerv::synth

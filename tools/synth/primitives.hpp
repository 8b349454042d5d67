// Solid primitives and their exact ray intersections. All are axis-aligned in
// the local frame of the object they belong to (x right, y up, z along its
// heading); the object transforms the ray, not the primitive.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace nerv::synth {

using Vec3 = Eigen::Vector3d;

enum class Shape : unsigned char {
  Box,        // centre c, half extents e
  CylinderY,  // vertical axis through c; e.x() = radius, e.y() = half height
  CylinderX,  // axis along x through c (wheels); e.x() = half length, e.y() = radius
  Sphere,     // centre c, e.x() = radius
};

struct PrimitiveHit {
  double t = 0;   // ray parameter
  Vec3 normal;    // outward unit normal (local frame)
};

// Nearest intersection of o + t d with t in (t_min, t_max). A ray starting
// inside the primitive sees no surface (we never render from inside solids).
bool intersect(Shape shape, const Vec3& c, const Vec3& e, const Vec3& o, const Vec3& d,
               double t_min, double t_max, PrimitiveHit& hit);

// Slab test against the box [lo, hi]; `inv_d` = 1 / d per component.
bool overlapsBox(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inv_d, double t_min,
                 double t_max);

}  // namespace nerv::synth

#include "primitives.hpp"

#include <cmath>
#include <limits>

namespace nerv::synth {
namespace {

bool box(const Vec3& c, const Vec3& e, const Vec3& o, const Vec3& d, double t_min, double t_max,
         PrimitiveHit& hit) {
  double t_near = -std::numeric_limits<double>::infinity();
  double t_far = std::numeric_limits<double>::infinity();
  int axis = -1;
  double sign = 0;
  for (int k = 0; k < 3; ++k) {
    const double lo = c[k] - e[k] - o[k], hi = c[k] + e[k] - o[k];
    if (d[k] == 0) {
      if (lo > 0 || hi < 0) return false;
      continue;
    }
    double t0 = lo / d[k], t1 = hi / d[k];
    double s = -1;  // entering through the low face: normal points to -k
    if (t0 > t1) {
      std::swap(t0, t1);
      s = 1;
    }
    if (t0 > t_near) {
      t_near = t0;
      axis = k;
      sign = s;
    }
    t_far = std::min(t_far, t1);
  }
  if (axis < 0 || t_near > t_far || t_near <= t_min || t_near >= t_max) return false;
  hit.t = t_near;
  hit.normal = Vec3::Zero();
  hit.normal[axis] = sign;
  return true;
}

// Infinite cylinder around axis `a` (0 = x, 1 = y) with caps at c[a] +- half.
bool cylinder(int a, const Vec3& c, double radius, double half, const Vec3& o, const Vec3& d,
              double t_min, double t_max, PrimitiveHit& hit) {
  const int p = a == 0 ? 1 : 0, q = 2;  // the two coordinates across the axis
  const double ox = o[p] - c[p], oz = o[q] - c[q];
  const double A = d[p] * d[p] + d[q] * d[q];
  bool found = false;
  double best = t_max;
  if (A > 0) {
    const double B = ox * d[p] + oz * d[q];
    const double C = ox * ox + oz * oz - radius * radius;
    const double disc = B * B - A * C;
    if (disc >= 0) {
      const double s = std::sqrt(disc);
      for (double t : {(-B - s) / A, (-B + s) / A}) {
        if (t <= t_min || t >= best) continue;
        const double along = o[a] + t * d[a] - c[a];
        if (std::abs(along) > half) continue;
        best = t;
        found = true;
        hit.t = t;
        hit.normal = Vec3::Zero();
        hit.normal[p] = (ox + t * d[p]) / radius;
        hit.normal[q] = (oz + t * d[q]) / radius;
        break;  // the smaller root that qualifies is the nearest
      }
    }
  }
  if (d[a] != 0) {
    for (double side : {-1.0, 1.0}) {
      const double t = (c[a] + side * half - o[a]) / d[a];
      if (t <= t_min || t >= best) continue;
      const double u = ox + t * d[p], v = oz + t * d[q];
      if (u * u + v * v > radius * radius) continue;
      best = t;
      found = true;
      hit.t = t;
      hit.normal = Vec3::Zero();
      hit.normal[a] = side;
    }
  }
  // A ray starting inside sees nothing (consistent with box()).
  if (found) {
    const double ux = o[p] - c[p], uz = o[q] - c[q];
    if (ux * ux + uz * uz < radius * radius && std::abs(o[a] - c[a]) < half) return false;
  }
  return found;
}

bool sphere(const Vec3& c, double r, const Vec3& o, const Vec3& d, double t_min, double t_max,
            PrimitiveHit& hit) {
  const Vec3 oc = o - c;
  const double A = d.squaredNorm(), B = oc.dot(d), C = oc.squaredNorm() - r * r;
  if (C < 0) return false;
  const double disc = B * B - A * C;
  if (disc < 0) return false;
  const double t = (-B - std::sqrt(disc)) / A;
  if (t <= t_min || t >= t_max) return false;
  hit.t = t;
  hit.normal = (oc + t * d) / r;
  return true;
}

}  // namespace

bool intersect(Shape shape, const Vec3& c, const Vec3& e, const Vec3& o, const Vec3& d,
               double t_min, double t_max, PrimitiveHit& hit) {
  switch (shape) {
    case Shape::Box: return box(c, e, o, d, t_min, t_max, hit);
    case Shape::CylinderY: return cylinder(1, c, e.x(), e.y(), o, d, t_min, t_max, hit);
    case Shape::CylinderX: return cylinder(0, c, e.y(), e.x(), o, d, t_min, t_max, hit);
    case Shape::Sphere: return sphere(c, e.x(), o, d, t_min, t_max, hit);
  }
  return false;
}

bool overlapsBox(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inv_d, double t_min,
                 double t_max) {
  for (int k = 0; k < 3; ++k) {
    double t0 = (lo[k] - o[k]) * inv_d[k], t1 = (hi[k] - o[k]) * inv_d[k];
    if (t0 > t1) std::swap(t0, t1);
    if (std::isnan(t0) || std::isnan(t1)) continue;  // 0 * inf: origin on the slab plane
    t_min = std::max(t_min, t0);
    t_max = std::min(t_max, t1);
    if (t_min > t_max) return false;
  }
  return true;
}

}  // namespace nerv::synth

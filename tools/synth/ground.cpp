#include "ground.hpp"

#include <cmath>

#include "noise.hpp"

namespace nerv::synth {
namespace {

// Intersection with the surface y = profile(z) + lift, split at the slope start.
bool profileSurface(const World& w, double lift, const Vec3& o, const Vec3& d, double t_min,
                    double t_max, double& t_out) {
  const double zs = w.road.slope_start_m, g = w.road.grade_percent * 0.01;
  bool found = false;
  if (d.y() != 0) {  // flat part
    const double t = (lift - o.y()) / d.y();
    if (t > t_min && t < t_max && o.z() + t * d.z() <= zs) {
      t_out = t;
      t_max = t;
      found = true;
    }
  }
  const double den = d.y() - g * d.z();
  if (g != 0 && den != 0) {  // y - g (z - zs) = lift
    const double t = (lift - g * zs - o.y() + g * o.z()) / den;
    if (t > t_min && t < t_max && o.z() + t * d.z() > zs) {
      t_out = t;
      found = true;
    }
  } else if (g == 0 && den != 0 && !found) {
    const double t = (lift - o.y()) / d.y();
    if (t > t_min && t < t_max) {
      t_out = t;
      found = true;
    }
  }
  return found;
}

}  // namespace

bool intersectGround(const World& w, const Vec3& o, const Vec3& d, double t_min, double t_max,
                     GroundHit& hit) {
  const double xl = w.road.roadLeft(), xr = w.road.roadRight(), curb = w.road.curb_height_m;
  bool found = false;
  double t;
  if (profileSurface(w, 0.0, o, d, t_min, t_max, t)) {
    const double x = o.x() + t * d.x();
    if (x >= xl && x <= xr) {
      found = true;
      t_max = t;
      hit.t = t;
      hit.zone = GroundZone::Road;
    }
  }
  if (profileSurface(w, curb, o, d, t_min, t_max, t)) {
    const double x = o.x() + t * d.x();
    if (x < xl || x > xr) {
      found = true;
      t_max = t;
      hit.t = t;
      const double beyond = x > xr ? x - xr : xl - x;
      hit.zone = beyond < w.road.sidewalk_width_m ? GroundZone::Sidewalk : GroundZone::Terrain;
    }
  }
  if (curb > 0) {
    for (double xc : {xl, xr}) {
      if (d.x() == 0) continue;
      t = (xc - o.x()) / d.x();
      if (t <= t_min || t >= t_max) continue;
      const double y = o.y() + t * d.y(), z = o.z() + t * d.z();
      const double base = w.profile(z);
      if (y < base || y > base + curb) continue;
      found = true;
      t_max = t;
      hit.t = t;
      hit.zone = GroundZone::Curb;
      hit.normal = Vec3(xc == xr ? -1 : 1, 0, 0);
    }
  }
  if (!found) return false;
  hit.point = o + hit.t * d;
  if (hit.zone != GroundZone::Curb) hit.normal = w.roadNormal(hit.point.z());
  return true;
}

int wetPatchAt(const World& w, const Vec3& p) {
  for (size_t i = 0; i < w.wet.size(); ++i) {
    const WetArea& a = w.wet[i];
    const double dx = (p.x() - a.x) / a.half_width, dz = (p.z() - a.z) / a.half_length;
    // A puddle: an ellipse with a ragged rim (noise on the radius).
    const double r = 1.0 + 0.18 * valueNoise(float(p.x() * 0.9), float(p.z() * 0.9), 4242u + i);
    if (dx * dx + dz * dz < r * r) return static_cast<int>(i);
  }
  return -1;
}

cv::Vec3f groundAlbedo(const World& w, const GroundHit& hit, float fp) {
  const float x = static_cast<float>(hit.point.x()), z = static_cast<float>(hit.point.z());
  const uint32_t seed = w.seed * 131u;
  switch (hit.zone) {
    case GroundZone::Road: {
      // Asphalt: patches of repair, wheel-track wear, aggregate grain at cm scale.
      const float patch = fbm(x, z, seed, 0.15f, 3, fp);
      const float mid = fbm(x, z, seed + 1, 1.5f, 4, fp);
      const float grain = fbm(x, z, seed + 2, 25.0f, 4, fp, 0.6f);
      float g = 92 + 10 * patch + 10 * mid + 26 * grain;
      // Sparse light stones.
      if (fp < 0.02f && hashUnit(int(std::floor(x * 60)), int(std::floor(z * 60)), seed + 3) > 0.97f)
        g += 35;
      cv::Vec3f c(g * 1.02f, g, g * 0.97f);
      if (!w.road.markings) return c;
      const RoadSpec& r = w.road;
      float paint = 0;
      // Edge lines (solid), centre line (solid if one lane each way, else dashed), lane lines dashed.
      const float lw = 0.15f;
      paint = std::max(paint, stripe(x - float(r.roadRight()) + 0.35f, 1000.0f, lw, fp));
      paint = std::max(paint, stripe(x - float(r.roadLeft()) - 0.2f, 1000.0f, lw, fp));
      const float dash = stripe(z, 9.0f, 3.0f, fp);
      for (int i = -r.lanes_left + 1; i < r.lanes_right; ++i) {
        const float xm = float(i * r.lane_width_m) - 0.5f * lw;
        const float across = stripe(x - xm, 1000.0f, lw, fp);
        paint = std::max(paint, i == 0 ? across : across * dash);
      }
      if (paint > 0) {
        const float wear = smoothstep(-0.2f, 0.5f, fbm(x, z, seed + 5, 3.0f, 4, fp));
        const float white = 205 + 20 * fbm(x, z, seed + 6, 20.0f, 3, fp);
        const float a = paint * (0.55f + 0.45f * wear);
        c = c * (1 - a) + cv::Vec3f(white, white, white * 0.98f) * a;
      }
      return c;
    }
    case GroundZone::Curb: {
      const float g = 165 + 18 * fbm(z, float(hit.point.y()), seed + 7, 4.0f, 4, fp) -
                      40 * stripe(z, 1.0f, 0.015f, fp);
      return {g, g, g};
    }
    case GroundZone::Sidewalk: {
      // Paving slabs 0.4 m with joints and per-slab shade.
      const int sx = int(std::floor(x / 0.4f)), sz = int(std::floor(z / 0.4f));
      const float shade = 0.9f + 0.2f * hashUnit(sx, sz, seed + 8);
      const float joint = std::max(stripe(x, 0.4f, 0.015f, fp), stripe(z, 0.4f, 0.015f, fp));
      const float g = (150 + 14 * fbm(x, z, seed + 9, 12.0f, 3, fp)) * shade * (1 - 0.35f * joint);
      return {g * 0.95f, g, g * 1.03f};
    }
    case GroundZone::Terrain: {
      const float clump = fbm(x, z, seed + 10, 0.4f, 3, fp);
      const float blade = fbm(x, z, seed + 11, 15.0f, 4, fp, 0.65f);
      const float k = 1.0f + 0.25f * clump + 0.35f * blade;
      return cv::Vec3f(45, 105, 75) * k;
    }
  }
  return {128, 128, 128};
}

}  // namespace nerv::synth

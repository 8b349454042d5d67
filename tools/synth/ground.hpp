// The ground as an analytic height field: the carriageway follows the road
// profile (flat, then an optional constant grade); sidewalks and the terrain
// beyond stand one curb height above it; vertical curb faces join the two.
#pragma once

#include <opencv2/core.hpp>

#include "world.hpp"

namespace nerv::synth {

enum class GroundZone : unsigned char { Road, Curb, Sidewalk, Terrain };

struct GroundHit {
  double t = 0;
  Vec3 point, normal;
  GroundZone zone = GroundZone::Road;
};

// Nearest ground intersection of o + t d with t in (t_min, t_max).
bool intersectGround(const World& w, const Vec3& o, const Vec3& d, double t_min, double t_max,
                     GroundHit& hit);

// Albedo (BGR) of the ground at a hit: asphalt with lane markings, curb
// stone, paving slabs, grass. `footprint` [m] filters the texture.
cv::Vec3f groundAlbedo(const World& w, const GroundHit& hit, float footprint);

// Index of the wet patch containing the road point, -1 if none.
int wetPatchAt(const World& w, const Vec3& p);

}  // namespace nerv::synth

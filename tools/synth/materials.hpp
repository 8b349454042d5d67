// Surface materials of solids: procedural albedo from local surface coordinates,
// deterministic from a per-object seed. Textures carry structure at several
// scales (stereo matchers need it) and are filtered by the pixel footprint.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

#include "primitives.hpp"

namespace nerv::synth {

enum class Material : unsigned char {
  Paint,       // car body: base colour, dirt, panel seams, lights
  Cabin,       // car greenhouse: glass with pillars, painted roof
  Tire,
  Cloth,       // clothes: colour, folds, stripes
  Skin,
  Metal,       // galvanised pole / bike frame
  StripedPost, // red-white delineator
  Sign,
  Bark,
  Foliage,
  Facade,      // wall with a grid of windows
  Fence,       // wooden / mesh fence with irregular boards
  Railing,     // strictly periodic bars (repetitive-texture trap)
  GuardRail,   // corrugated steel beam
  PlainWhite,  // textureless panel (trap)
  Concrete,
};

struct Surface {
  Material material = Material::Concrete;
  cv::Vec3f colour{128, 128, 128};  // base colour, BGR 0..255
};

// Albedo (BGR 0..255) at surface coordinates (u, v) [m] (v = height for upright
// faces) of the local point `p` with local normal `n`; `footprint` is the size
// of a sample on the surface [m], `seed` the object's texture seed.
cv::Vec3f albedo(const Surface& s, float u, float v, const Vec3& p, const Vec3& n,
                 float footprint, uint32_t seed);

}  // namespace nerv::synth

#include "materials.hpp"

#include <cmath>

#include "noise.hpp"

namespace nerv::synth {
namespace {

cv::Vec3f grey(float g) { return {g, g, g}; }

cv::Vec3f facade(const cv::Vec3f& wall, float u, float v, float fp, uint32_t seed) {
  // Plaster/brick: broad stains and fine grain.
  const float stain = fbm(u, v, seed, 0.5f, 3, fp);
  const float grain = fbm(u, v, seed + 1, 8.0f, 4, fp);
  cv::Vec3f c = wall * (1.0f + 0.10f * stain + 0.12f * grain);
  // Windows: 3.2 m bays, 3 m floors, each window its own glass and blind.
  const float bay = 3.2f, floor_h = 3.0f;
  const int col = static_cast<int>(std::floor(u / bay));
  const int row = static_cast<int>(std::floor(v / floor_h));
  const float cu = u - col * bay, cv_ = v - row * floor_h;
  const bool shop = row == 0;
  const float w0 = shop ? 0.3f : 0.9f, w1 = shop ? 2.9f : 2.3f;
  const float h0 = shop ? 0.4f : 0.9f, h1 = shop ? 2.6f : 2.4f;
  const float inside_u = stripe(cu - w0, bay, w1 - w0, fp);
  const float inside_v = (cv_ > h0 && cv_ < h1) ? 1.0f : 0.0f;
  const float win = inside_u * inside_v;
  if (win > 0) {
    const float r = hashUnit(col, row, seed + 17);
    const float blind = hashUnit(col, row, seed + 29);
    float g = 35 + 45 * r + 20 * fbm(u, v, seed + 3, 1.5f, 3, fp);
    if (r > 0.85f) g = 150 + 40 * fbm(u, v, seed + 5, 3.0f, 2, fp);  // lit room
    if (cv_ > h1 - (h1 - h0) * blind * 0.6f) g = 150 + 25 * fbm(u, v * 8, seed + 7, 2.0f, 2, fp);
    const cv::Vec3f glass(g * 1.05f, g, g * 0.95f);
    // Frame: a light border around the glass.
    const float edge = std::min(std::min(cu - w0, w1 - cu), std::min(cv_ - h0, h1 - cv_));
    const cv::Vec3f inner = edge < 0.07f ? grey(200) : glass;
    c = c * (1 - win) + inner * win;
  }
  return c;
}

}  // namespace

cv::Vec3f albedo(const Surface& s, float u, float v, const Vec3& p, const Vec3& n,
                 float fp, uint32_t seed) {
  const cv::Vec3f& base = s.colour;
  switch (s.material) {
    case Material::Paint: {
      const float broad = fbm(u, v, seed, 0.7f, 3, fp);
      const float dirt = fbm(u, v, seed + 11, 5.0f, 4, fp);
      const float speck = fbm(u, v, seed + 13, 40.0f, 2, fp);
      cv::Vec3f c = base * (1.0f + 0.08f * broad + 0.10f * dirt + 0.06f * speck);
      // Panel seams and a darker sill/bumper band near the ground.
      const float seam = stripe(u + 0.3f, 1.35f, 0.025f, fp);
      c *= 1.0f - 0.45f * seam;
      if (p.y() < 0.38) c = grey(45 + 15 * dirt) * 0.8f + c * 0.2f;
      return c;
    }
    case Material::Cabin: {
      if (n.y() > 0.7) return base * (1.0f + 0.08f * fbm(u, v, seed, 2.0f, 4, fp));
      // Glass reflecting the street: streaks stretched along the window.
      const float refl = fbm(u * 0.7f, v * 3.0f, seed + 21, 1.5f, 4, fp);
      const float fine = fbm(u, v, seed + 23, 12.0f, 3, fp);
      const float pillar = stripe(u + 0.1f, 1.6f, 0.12f, fp);
      const cv::Vec3f glass = grey(55 + 35 * refl + 10 * fine);
      return glass * (1 - pillar) + base * 0.7f * pillar;
    }
    case Material::Tire:
      return grey(32 + 10 * fbm(u, v, seed, 6.0f, 3, fp) + 8 * stripe(v, 0.05f, 0.02f, fp));
    case Material::Cloth: {
      const float folds = fbm(u * 0.5f, v * 2.0f, seed, 3.0f, 4, fp);
      const float weave = fbm(u, v, seed + 3, 30.0f, 2, fp);
      const float band = (seed % 3 == 0) ? stripe(v, 0.12f, 0.05f, fp) : 0.0f;
      return base * (1.0f + 0.22f * folds + 0.08f * weave) * (1.0f - 0.35f * band);
    }
    case Material::Skin:
      return base * (1.0f + 0.08f * fbm(u, v, seed, 8.0f, 3, fp));
    case Material::Metal: {
      const float scratch = fbm(u * 8.0f, v * 0.5f, seed, 2.0f, 3, fp);
      return base * (1.0f + 0.10f * fbm(u, v, seed + 1, 2.0f, 4, fp) + 0.06f * scratch);
    }
    case Material::StripedPost: {
      const float red = stripe(v, 0.5f, 0.25f, fp);
      const cv::Vec3f c = cv::Vec3f(40, 40, 190) * red + grey(225) * (1 - red);
      return c * (1.0f + 0.06f * fbm(u, v, seed, 10.0f, 3, fp));
    }
    case Material::Sign:
      return base * (1.0f + 0.06f * fbm(u, v, seed, 6.0f, 3, fp));
    case Material::Bark: {
      const float ridges = fbm(u * 6.0f, v * 0.7f, seed, 2.0f, 4, fp, 0.6f);
      return base * (1.0f + 0.35f * ridges + 0.1f * fbm(u, v, seed + 1, 20.0f, 2, fp));
    }
    case Material::Foliage: {
      const float leaves = fbm(u, v, seed, 1.5f, 6, fp, 0.7f);
      const float gaps = smoothstep(0.25f, 0.6f, fbm(u, v, seed + 9, 3.0f, 3, fp));
      cv::Vec3f c = base * (0.75f + 0.55f * leaves);
      return c * (1.0f - 0.5f * gaps);
    }
    case Material::Facade:
      return facade(base, u, v, fp, seed);
    case Material::Fence: {
      // Boards 0.12 m wide, each with its own shade and grain.
      const int board = static_cast<int>(std::floor(u / 0.12f));
      const float shade = 0.8f + 0.35f * hashUnit(board, 0, seed);
      const float grain = fbm(u * 4.0f, v * 0.5f, seed + board, 3.0f, 4, fp);
      const float gap = stripe(u, 0.12f, 0.012f, fp);
      return base * shade * (1.0f + 0.15f * grain) * (1.0f - 0.6f * gap);
    }
    case Material::Railing: {
      // Identical bars every 0.14 m and two rails: nothing tells one bar from the next.
      const float bar = stripe(u, 0.14f, 0.045f, fp);
      const float rail = std::max(stripe(v - 0.05f, 100.0f, 0.08f, fp),
                                  stripe(v - 1.02f, 100.0f, 0.08f, fp));
      const float dark = std::max(bar, rail);
      return grey(40) * dark + grey(185) * (1 - dark);
    }
    case Material::GuardRail: {
      const float wave = std::cos(v * 6.2831853f / 0.11f) * (fp < 0.04f ? 1.0f : 0.0f);
      return base * (1.0f + 0.12f * wave + 0.05f * fbm(u, v, seed, 3.0f, 3, fp));
    }
    case Material::PlainWhite:
      return grey(236 + 1.0f * fbm(u, v, seed, 1.0f, 2, fp));
    case Material::Concrete:
      return base * (1.0f + 0.08f * fbm(u, v, seed, 0.8f, 3, fp) +
                     0.10f * fbm(u, v, seed + 1, 10.0f, 4, fp));
  }
  (void)n;
  return base;
}

}  // namespace nerv::synth

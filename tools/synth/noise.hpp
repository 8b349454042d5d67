// Procedural noise for textures: integer-lattice hashing (deterministic from a
// seed, no tables), value noise and band-limited fractal sums. Band limiting is
// the texture filter: octaves finer than the pixel footprint are faded out, so
// distant surfaces blur instead of aliasing.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace nerv::synth {

inline uint32_t hash2(int32_t x, int32_t y, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B1u + 0x7F4A7C15u;
  h ^= static_cast<uint32_t>(x) * 0x85EBCA6Bu;
  h = (h << 13) | (h >> 19);
  h = h * 5u + 0xE6546B64u;
  h ^= static_cast<uint32_t>(y) * 0xC2B2AE35u;
  h = (h << 13) | (h >> 19);
  h = h * 5u + 0xE6546B64u;
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return h;
}

// Uniform in [0, 1).
inline float hashUnit(int32_t x, int32_t y, uint32_t seed) {
  return static_cast<float>(hash2(x, y, seed) >> 8) * (1.0f / 16777216.0f);
}

// Smoothly interpolated lattice noise in [-1, 1].
inline float valueNoise(float x, float y, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int32_t ix = static_cast<int32_t>(fx), iy = static_cast<int32_t>(fy);
  float tx = x - fx, ty = y - fy;
  tx = tx * tx * (3 - 2 * tx);
  ty = ty * ty * (3 - 2 * ty);
  const float a = hashUnit(ix, iy, seed), b = hashUnit(ix + 1, iy, seed);
  const float c = hashUnit(ix, iy + 1, seed), d = hashUnit(ix + 1, iy + 1, seed);
  const float top = a + (b - a) * tx, bottom = c + (d - c) * tx;
  return 2.0f * (top + (bottom - top) * ty) - 1.0f;
}

// Fractal sum of `octaves` value-noise octaves starting at `frequency` [1/m],
// each twice as fine and `gain` times as strong. Octaves whose wavelength is
// below two footprints [m] are faded out; the result keeps the normalisation of
// the full sum, so filtered-away detail lowers the contrast as real blur does.
inline float fbm(float x, float y, uint32_t seed, float frequency, int octaves,
                 float footprint, float gain = 0.5f) {
  float sum = 0, norm = 0, amp = 1;
  for (int i = 0; i < octaves; ++i) {
    norm += amp;
    const float cycles = frequency * footprint;  // cycles per footprint
    if (cycles < 0.5f) {
      const float fade = cycles < 0.25f ? 1.0f : (0.5f - cycles) * 4.0f;
      sum += amp * fade * valueNoise(x * frequency, y * frequency, seed + 7919u * i);
    }
    amp *= gain;
    frequency *= 2;
  }
  return sum / norm;
}

// Fraction of a 1-D stripe pattern covered, filtered over the footprint:
// stripes of width `width` repeating every `period`, starting at 0.
inline float stripe(float x, float period, float width, float footprint) {
  const float p = x / period - std::floor(x / period);
  const float w = width / period;
  const float f = std::max(footprint / period, 1e-4f);
  if (f >= 0.5f) return w;  // unresolved: mean coverage
  // Coverage of [p - f/2, p + f/2] by [0, w] on the unit circle (box filter).
  auto integral = [w](float t) {  // measure of [0, t] ∩ stripes, t any real
    const float n = std::floor(t);
    return n * w + std::min(t - n, w);
  };
  return (integral(p + 0.5f * f) - integral(p - 0.5f * f)) / f;
}

inline float clamp01(float v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }
inline float smoothstep(float a, float b, float x) {
  const float t = clamp01((x - a) / (b - a));
  return t * t * (3 - 2 * t);
}

}  // namespace nerv::synth

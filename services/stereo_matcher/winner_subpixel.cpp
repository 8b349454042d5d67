#include "winner_subpixel.hpp"

#include <algorithm>
#include <cstdlib>

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace nerv::stereo {

float equiangularOffset(int a, int b, int c) {
  // Equal slopes on both sides: the steeper measured side gives the slope.
  const int slope = std::max(a - b, c - b);
  if (slope <= 0) return 0.0f;
  return std::clamp(0.5f * static_cast<float>(a - c) / static_cast<float>(slope), -0.5f, 0.5f);
}

namespace {

// First index of the minimum of D uint16 values.
inline int argminFirst(const uint16_t* s, int D, uint16_t& min_value) {
#ifdef __AVX2__
  if (D % 16 == 0) {
    __m256i m = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s));
    for (int d = 16; d < D; d += 16)
      m = _mm256_min_epu16(m, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + d)));
    const __m128i h = _mm_min_epu16(_mm256_castsi256_si128(m), _mm256_extracti128_si256(m, 1));
    min_value = static_cast<uint16_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(h)));
    const __m256i target = _mm256_set1_epi16(static_cast<short>(min_value));
    for (int d = 0; d < D; d += 16) {
      const __m256i eq =
          _mm256_cmpeq_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + d)), target);
      const unsigned mask = static_cast<unsigned>(_mm256_movemask_epi8(eq));
      if (mask) return d + __builtin_ctz(mask) / 2;
    }
  }
#endif
  int best = 0;
  for (int d = 1; d < D; ++d)
    if (s[d] < s[best]) best = d;
  min_value = s[best];
  return best;
}

// Smallest cost with |d - d1| > 1 (s1 when there is none, D <= 3).
inline int secondBest(const uint16_t* s, int D, int d1, uint16_t s1) {
  uint16_t second = 0xffff;
#ifdef __AVX2__
  if (D % 16 == 0) {
    // lanes d1 - 1 .. d1 + 1 are masked to 0xffff by an index compare
    const __m256i lanes = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m256i lo = _mm256_set1_epi16(static_cast<short>(d1 - 2));
    const __m256i hi = _mm256_set1_epi16(static_cast<short>(d1 + 2));
    __m256i m = _mm256_set1_epi16(-1);
    for (int d = 0; d < D; d += 16) {
      const __m256i idx = _mm256_add_epi16(lanes, _mm256_set1_epi16(static_cast<short>(d)));
      const __m256i near = _mm256_and_si256(_mm256_cmpgt_epi16(idx, lo), _mm256_cmpgt_epi16(hi, idx));
      const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + d));
      m = _mm256_min_epu16(m, _mm256_or_si256(v, near));
    }
    const __m128i h = _mm_min_epu16(_mm256_castsi256_si128(m), _mm256_extracti128_si256(m, 1));
    second = static_cast<uint16_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(h)));
  } else
#endif
  {
    for (int d = 0; d < D; ++d)
      if (d < d1 - 1 || d > d1 + 1) second = std::min(second, s[d]);
  }
  return second == 0xffff && D <= 3 ? s1 : second;
}

}  // namespace

void selectLeftWinners(const uint16_t* S, int cols, int D, WinnerOptions opt, int16_t* best,
                       float* disparity, float* confidence) {
  for (int x = 0; x < cols; ++x) {
    const uint16_t* s = S + static_cast<size_t>(x) * D;
    uint16_t s1 = 0;
    const int d1 = argminFirst(s, D, s1);
    const int s2 = secondBest(s, D, d1, s1);
    if (opt.uniqueness_ratio > 0 && s2 * (100 - opt.uniqueness_ratio) < s1 * 100) {
      best[x] = -1;
      disparity[x] = -1.0f;
      confidence[x] = 0.0f;
      continue;
    }
    best[x] = static_cast<int16_t>(d1);
    float offset = 0.0f;
    if (opt.subpixel && d1 > 0 && d1 + 1 < D) offset = equiangularOffset(s[d1 - 1], s1, s[d1 + 1]);
    disparity[x] = static_cast<float>(d1) + offset;
    confidence[x] = s2 > 0 ? static_cast<float>(s2 - s1) / static_cast<float>(s2) : 0.0f;
  }
}

void selectRightWinners(const uint16_t* S, int cols, int D, int min_disparity, int16_t* best_right,
                        std::vector<uint16_t>& cost, std::vector<int16_t>& index) {
  // Reversed right index j = cols - 1 - xr = (cols - 1 - x) + min_disparity + d
  // makes a left pixel's D candidates contiguous: a vectorisable running minimum.
  const int n = cols + min_disparity + D;
  cost.assign(n, 0xffff);
  index.assign(n, -1);
  for (int x = 0; x < cols; ++x) {
    const uint16_t* s = S + static_cast<size_t>(x) * D;
    uint16_t* c = cost.data() + (cols - 1 - x) + min_disparity;
    int16_t* i = index.data() + (cols - 1 - x) + min_disparity;
    for (int d = 0; d < D; ++d) {
      const bool better = s[d] < c[d];  // strict: x grows with d, so ties keep the smallest d
      c[d] = better ? s[d] : c[d];
      i[d] = better ? static_cast<int16_t>(d) : i[d];
    }
  }
  for (int xr = 0; xr < cols; ++xr) best_right[xr] = index[cols - 1 - xr];
}

}  // namespace nerv::stereo

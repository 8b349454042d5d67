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
inline int secondBest(uint16_t* s, int D, int d1, uint16_t s1) {
  uint16_t second = 0xffff;
#ifdef __AVX2__
  if (D % 16 == 0) {
    // Mask d1 - 1 .. d1 + 1 in place (three scalar stores, restored below):
    // cheaper than building an index mask for every vector.
    uint16_t saved[3];
    for (int i = 0; i < 3; ++i) {
      const int d = d1 - 1 + i;
      if (d >= 0 && d < D) {
        saved[i] = s[d];
        s[d] = 0xffff;
      }
    }
    __m256i m = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s));
    for (int d = 16; d < D; d += 16)
      m = _mm256_min_epu16(m, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + d)));
    const __m128i h = _mm_min_epu16(_mm256_castsi256_si128(m), _mm256_extracti128_si256(m, 1));
    second = static_cast<uint16_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(h)));
    for (int i = 0; i < 3; ++i) {
      const int d = d1 - 1 + i;
      if (d >= 0 && d < D) s[d] = saved[i];
    }
  } else
#endif
  {
    for (int d = 0; d < D; ++d)
      if (d < d1 - 1 || d > d1 + 1) second = std::min(second, s[d]);
  }
  return second == 0xffff && D <= 3 ? s1 : second;
}

}  // namespace

namespace {

// Decision for one pixel from its D aggregated costs.
inline void decide(uint16_t* s, int D, int d1, uint16_t s1, WinnerOptions opt, int16_t& best,
                   float& disparity, float& confidence) {
  const int s2 = secondBest(s, D, d1, s1);
  if (opt.uniqueness_ratio > 0 && s2 * (100 - opt.uniqueness_ratio) < s1 * 100) {
    best = -1;
    disparity = -1.0f;
    confidence = 0.0f;
    return;
  }
  best = static_cast<int16_t>(d1);
  float offset = 0.0f;
  if (opt.subpixel && d1 > 0 && d1 + 1 < D) offset = equiangularOffset(s[d1 - 1], s1, s[d1 + 1]);
  disparity = static_cast<float>(d1) + offset;
  confidence = s2 > 0 ? static_cast<float>(s2 - s1) / static_cast<float>(s2) : 0.0f;
}

}  // namespace

void selectLeftWinners(uint16_t* S, int cols, int D, WinnerOptions opt, int16_t* best,
                       float* disparity, float* confidence) {
  for (int x = 0; x < cols; ++x) {
    uint16_t* s = S + static_cast<size_t>(x) * D;
    uint16_t s1 = 0;
    const int d1 = argminFirst(s, D, s1);
    decide(s, D, d1, s1, opt, best[x], disparity[x], confidence[x]);
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

void selectWinnersFromPaths(const uint8_t* const paths[4], int cols, int D, int min_disparity,
                            WinnerOptions opt, int16_t* best, float* disparity, float* confidence,
                            int16_t* best_right, std::vector<uint16_t>& sum,
                            std::vector<uint16_t>& cost, std::vector<int16_t>& index) {
#ifdef __AVX2__
  if (D % 32 == 0 && D <= 512) {
    sum.resize(D);
    // Right view without a scattered running minimum: the candidate (x, d) and
    // (x - 1, d - 1) belong to the same right pixel, so the best candidate so
    // far per right pixel is a D-vector shifted by one lane per left pixel:
    // best_x[d] = min(S(x, d), best_{x-1}[d - 1]); lane D - 1 is final then.
    // Sums are <= 4 * 255, so signed 16-bit compares suffice.
    alignas(32) int16_t run_cost[512];
    alignas(32) int16_t run_index[512];
    if (best_right) {
      std::fill(run_cost, run_cost + D, int16_t{0x7fff});
      std::fill(run_index, run_index + D, int16_t{-1});
      std::fill(best_right, best_right + cols, int16_t{-1});
    }
    const __m256i lanes = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m256i none = _mm256_set1_epi16(0x7fff), no_index = _mm256_set1_epi16(-1);
    uint16_t* s = sum.data();
    auto load = [](const void* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); };
    auto widen_lo = [](__m256i v) { return _mm256_cvtepu8_epi16(_mm256_castsi256_si128(v)); };
    auto widen_hi = [](__m256i v) { return _mm256_cvtepu8_epi16(_mm256_extracti128_si256(v, 1)); };
    // lane i of the result = lane i - 1 of cur (lane 0 = last lane of below)
    auto shift_in = [](__m256i cur, __m256i below) {
      return _mm256_alignr_epi8(cur, _mm256_permute2x128_si256(below, cur, 0x21), 14);
    };
    for (int x = 0; x < cols; ++x) {
      const size_t o = static_cast<size_t>(x) * D;
      __m256i vmin = _mm256_set1_epi16(-1);
      // the two vertical-path rows stream from the volumes in memory: fetch ahead
      for (int k = 0; k < D; k += 64) {
        _mm_prefetch(reinterpret_cast<const char*>(paths[2] + o + 4 * D + k), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(paths[3] + o + 4 * D + k), _MM_HINT_T0);
      }
      __m256i below_cost = none, below_index = no_index;  // best_{x-1}[-1]: no candidate yet
      for (int k = 0; k < D; k += 32) {
        const __m256i a = load(paths[0] + o + k), b = load(paths[1] + o + k),
                      c = load(paths[2] + o + k), e = load(paths[3] + o + k);
        const __m256i halves[2] = {
            _mm256_add_epi16(_mm256_add_epi16(widen_lo(a), widen_lo(b)),
                             _mm256_add_epi16(widen_lo(c), widen_lo(e))),
            _mm256_add_epi16(_mm256_add_epi16(widen_hi(a), widen_hi(b)),
                             _mm256_add_epi16(widen_hi(c), widen_hi(e)))};
        for (int h = 0; h < 2; ++h) {
          const int kk = k + 16 * h;
          const __m256i v = halves[h];
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(s + kk), v);
          vmin = _mm256_min_epu16(vmin, v);
          if (best_right) {
            const __m256i prev_cost = load(run_cost + kk), prev_index = load(run_index + kk);
            const __m256i shifted_cost = shift_in(prev_cost, below_cost);
            const __m256i shifted_index = shift_in(prev_index, below_index);
            below_cost = prev_cost;
            below_index = prev_index;
            // strict: an earlier (smaller d) candidate keeps a tie
            const __m256i better = _mm256_cmpgt_epi16(shifted_cost, v);
            const __m256i d = _mm256_add_epi16(lanes, _mm256_set1_epi16(static_cast<short>(kk)));
            _mm256_store_si256(reinterpret_cast<__m256i*>(run_cost + kk), _mm256_min_epi16(shifted_cost, v));
            _mm256_store_si256(reinterpret_cast<__m256i*>(run_index + kk),
                               _mm256_blendv_epi8(shifted_index, d, better));
          }
        }
      }
      if (best_right) {
        const int xr = x - min_disparity - (D - 1);  // its last candidate was (x, D - 1)
        if (xr >= 0) best_right[xr] = run_index[D - 1];
      }
      const __m128i hmin = _mm_min_epu16(_mm256_castsi256_si128(vmin), _mm256_extracti128_si256(vmin, 1));
      const uint16_t s1 = static_cast<uint16_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(hmin)));
      const __m256i target = _mm256_set1_epi16(static_cast<short>(s1));
      int d1 = 0;
      for (int d = 0; d < D; d += 16) {
        const unsigned mask = static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi16(
            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + d)), target)));
        if (mask) {
          d1 = d + __builtin_ctz(mask) / 2;
          break;
        }
      }
      decide(s, D, d1, s1, opt, best[x], disparity[x], confidence[x]);
    }
    if (best_right)  // right pixels whose candidates ended at the row's last pixel
      for (int d = 0; d + 1 < D; ++d) {
        const int xr = cols - 1 - min_disparity - d;
        if (xr >= 0 && xr < cols) best_right[xr] = run_index[d];
      }
    (void)cost;
    (void)index;
    return;
  }
#endif
  sum.resize(static_cast<size_t>(cols) * D);
  for (size_t k = 0; k < sum.size(); ++k)
    sum[k] = static_cast<uint16_t>(paths[0][k] + paths[1][k] + paths[2][k] + paths[3][k]);
  selectLeftWinners(sum.data(), cols, D, opt, best, disparity, confidence);
  if (best_right) selectRightWinners(sum.data(), cols, D, min_disparity, best_right, cost, index);
}

}  // namespace nerv::stereo

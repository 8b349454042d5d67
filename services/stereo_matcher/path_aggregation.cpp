#include "path_aggregation.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#ifdef __AVX2__
#include <immintrin.h>
#elif defined(__ARM_NEON)
#include <arm_neon.h>
#define NERV_PATH_STEP_128 1
#elif defined(__SSE4_1__)
#include <smmintrin.h>
#define NERV_PATH_STEP_128 1
#endif

namespace nerv::stereo {

namespace {

#ifdef __AVX2__
// The AVX2 step. D costs of the previous pixel sit in D/32 registers; the
// d-1 / d+1 neighbours are the register shifted by one byte across the
// 128-bit lanes (permute2x128 + alignr), with 255 shifted in at both ends.
// stream (32-byte aligned, or nullptr): a second copy of out written with
// non-temporal stores (the vertical paths' volume).
__attribute__((always_inline)) inline uint8_t stepAvx2(const uint8_t* cost, const uint8_t* prev,
                                                       uint8_t prev_min, uint8_t* out, int D,
                                                       __m256i p1v, __m256i p2v,
                                                       uint8_t* stream = nullptr) {
  const __m256i minv = _mm256_set1_epi8(static_cast<char>(prev_min));
  const __m256i jump = _mm256_adds_epu8(minv, p2v);
  const __m256i full = _mm256_set1_epi8(static_cast<char>(0xff));
  __m256i below = full;
  __m256i cur = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(prev));
  __m256i running = full;
  for (int k = 0; k < D; k += 32) {
    const __m256i above =
        k + 32 < D ? _mm256_loadu_si256(reinterpret_cast<const __m256i*>(prev + k + 32)) : full;
    const __m256i minus1 =
        _mm256_alignr_epi8(cur, _mm256_permute2x128_si256(below, cur, 0x21), 15);  // L(d-1)
    const __m256i plus1 =
        _mm256_alignr_epi8(_mm256_permute2x128_si256(cur, above, 0x21), cur, 1);   // L(d+1)
    const __m256i m = _mm256_min_epu8(
        _mm256_min_epu8(cur, _mm256_adds_epu8(minus1, p1v)),
        _mm256_min_epu8(_mm256_adds_epu8(plus1, p1v), jump));
    const __m256i c = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(cost + k));
    const __m256i v = _mm256_adds_epu8(_mm256_sub_epi8(m, minv), c);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + k), v);
    if (stream) _mm256_stream_si256(reinterpret_cast<__m256i*>(stream + k), v);
    running = _mm256_min_epu8(running, v);
    below = cur;
    cur = above;
  }
  // Horizontal minimum of 32 bytes: fold to 16, pair bytes into 16-bit lanes, minpos.
  __m128i x = _mm_min_epu8(_mm256_castsi256_si128(running), _mm256_extracti128_si256(running, 1));
  x = _mm_min_epu8(x, _mm_srli_epi16(x, 8));
  return static_cast<uint8_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(x)));
}
#endif

#ifdef NERV_PATH_STEP_128
// The same step on 16 disparities a register, for targets without AVX2: NEON (ARM) or
// SSE4.1 (x86-64-v2). The compiler vectorises pathStepScalar too, but only its interior,
// with the saturation written out; this one is the AVX2 step's arithmetic, register for
// register (stereoSgm.PathStepSimdEqualsScalar).
#if defined(__ARM_NEON)
using V16 = uint8x16_t;
inline V16 load16(const uint8_t* p) { return vld1q_u8(p); }
inline void store16(uint8_t* p, V16 v) { vst1q_u8(p, v); }
inline V16 splat16(uint8_t x) { return vdupq_n_u8(x); }
inline V16 adds16(V16 a, V16 b) { return vqaddq_u8(a, b); }
inline V16 sub16(V16 a, V16 b) { return vsubq_u8(a, b); }
inline V16 min16(V16 a, V16 b) { return vminq_u8(a, b); }
inline V16 lower16(V16 below, V16 cur) { return vextq_u8(below, cur, 15); }  // below[15], cur[0..14]
inline V16 upper16(V16 cur, V16 above) { return vextq_u8(cur, above, 1); }   // cur[1..15], above[0]
inline uint8_t hmin16(V16 v) { return vminvq_u8(v); }
#else
using V16 = __m128i;
inline V16 load16(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
inline void store16(uint8_t* p, V16 v) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v); }
inline V16 splat16(uint8_t x) { return _mm_set1_epi8(static_cast<char>(x)); }
inline V16 adds16(V16 a, V16 b) { return _mm_adds_epu8(a, b); }
inline V16 sub16(V16 a, V16 b) { return _mm_sub_epi8(a, b); }
inline V16 min16(V16 a, V16 b) { return _mm_min_epu8(a, b); }
inline V16 lower16(V16 below, V16 cur) { return _mm_alignr_epi8(cur, below, 15); }
inline V16 upper16(V16 cur, V16 above) { return _mm_alignr_epi8(above, cur, 1); }
inline uint8_t hmin16(V16 v) {  // pairs of bytes into 16-bit lanes, then minpos
  return static_cast<uint8_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(_mm_min_epu8(v, _mm_srli_epi16(v, 8)))));
}
#endif

__attribute__((always_inline)) inline uint8_t step128(const uint8_t* cost, const uint8_t* prev,
                                                      uint8_t prev_min, uint8_t* out, int D, V16 p1v,
                                                      V16 p2v) {
  const V16 minv = splat16(prev_min);
  const V16 jump = adds16(minv, p2v);
  const V16 full = splat16(255);
  V16 below = full, cur = load16(prev), running = full;
  for (int k = 0; k < D; k += 16) {
    const V16 above = k + 16 < D ? load16(prev + k + 16) : full;
    const V16 m = min16(min16(cur, adds16(lower16(below, cur), p1v)),
                        min16(adds16(upper16(cur, above), p1v), jump));
    const V16 v = adds16(sub16(m, minv), load16(cost + k));
    store16(out + k, v);
    running = min16(running, v);
    below = cur;
    cur = above;
  }
  return hmin16(running);
}
#endif

}  // namespace

bool pathSimdAvailable() {
#if defined(__AVX2__) || defined(NERV_PATH_STEP_128)
  return true;
#else
  return false;
#endif
}

const char* pathStepPath() {
#if defined(__AVX2__)
  return "AVX2";
#elif defined(NERV_PATH_STEP_128) && defined(__ARM_NEON)
  return "NEON";
#elif defined(NERV_PATH_STEP_128)
  return "SSE4.1";
#else
  return "portable loop";
#endif
}

// Written so that GCC vectorises it on any target (SSE2, NEON): no branch in the loop.
// Nothing is lost by leaving out the neighbours beyond the ends (255 + P1 never beats
// prev[d] <= 255) and the clamps inside the minimum (prev[d] <= 255 is always among its
// terms); m - prev_min >= 0 since prev_min is prev's minimum and the jump adds to it.
// Until the third session of 2026-12-07 the loop branched at the ends and clamped each
// term: a build without AVX2 (-march=x86-64-v2) took 500 ms a KITTI frame, 63 % of it here.
uint8_t pathStepScalar(const uint8_t* cost, const uint8_t* prev, uint8_t prev_min, uint8_t* out,
                       int D, PathPenalties pen) {
  const int jump = prev_min + pen.p2, p1 = pen.p1, base = prev_min;
  auto step = [&](int d, int lower, int upper) {
    const int m = std::min(std::min(static_cast<int>(prev[d]), lower + p1), std::min(upper + p1, jump));
    return static_cast<uint8_t>(std::min(m - base + cost[d], 255));
  };
  if (D == 1) return out[0] = step(0, 255, 255);
  out[0] = step(0, 255, prev[1]);
  out[D - 1] = step(D - 1, prev[D - 2], 255);
  uint8_t running = std::min(out[0], out[D - 1]);
  // The interior in bytes (16 a step with SSE2): a + b saturated as a + min(b, 255 - a).
  // The clamps change no minimum (above), and m >= prev_min, so this is the same step.
  const uint8_t* __restrict pv = prev;
  const uint8_t* __restrict cv = cost;
  uint8_t* __restrict ov = out;
  const uint8_t p1b = static_cast<uint8_t>(std::min(p1, 255)), jumpb = static_cast<uint8_t>(std::min(jump, 255));
  const uint8_t baseb = prev_min;
  auto sat = [](uint8_t a, uint8_t b) { return static_cast<uint8_t>(a + std::min(b, static_cast<uint8_t>(255 - a))); };
  for (int d = 1; d < D - 1; ++d) {
    const uint8_t m = std::min(std::min(pv[d], sat(pv[d - 1], p1b)), std::min(sat(pv[d + 1], p1b), jumpb));
    const uint8_t v = sat(static_cast<uint8_t>(m - baseb), cv[d]);
    ov[d] = v;
    running = std::min(running, v);
  }
  return running;
}

uint8_t pathStepSimd(const uint8_t* cost, const uint8_t* prev, uint8_t prev_min, uint8_t* out,
                     int D, PathPenalties pen) {
#ifdef __AVX2__
  if (D % 32 == 0)
    return stepAvx2(cost, prev, prev_min, out, D, _mm256_set1_epi8(static_cast<char>(pen.p1)),
                    _mm256_set1_epi8(static_cast<char>(pen.p2)));
#elif defined(NERV_PATH_STEP_128)
  if (D % 16 == 0)
    return step128(cost, prev, prev_min, out, D, splat16(static_cast<uint8_t>(pen.p1)),
                   splat16(static_cast<uint8_t>(pen.p2)));
#endif
  return pathStepScalar(cost, prev, prev_min, out, D, pen);
}

namespace {
// Both directions of a row in one loop: two independent dependency chains per iteration
// keep the core busy while each waits on its horizontal minimum. step(cost, prev, prev_min,
// out) is one of the steps above.
template <class Step>
__attribute__((always_inline)) inline void walkRowBothWays(const uint8_t* cost, int cols, int D,
                                                           const uint8_t* zeros, uint8_t* forward,
                                                           uint8_t* backward, Step step) {
  uint8_t min_fwd = 0, min_bwd = 0;
  const uint8_t* prev_fwd = zeros;
  const uint8_t* prev_bwd = zeros;
  for (int i = 0; i < cols; ++i) {
    const size_t f = static_cast<size_t>(i) * D, b = static_cast<size_t>(cols - 1 - i) * D;
    min_fwd = step(cost + f, prev_fwd, min_fwd, forward + f);
    min_bwd = step(cost + b, prev_bwd, min_bwd, backward + b);
    prev_fwd = forward + f;
    prev_bwd = backward + b;
  }
}
}  // namespace

void aggregateRowHorizontal(const uint8_t* cost, int cols, int D, PathPenalties pen, bool simd,
                            uint8_t* forward, uint8_t* backward) {
  if (cols <= 0) return;
  const std::vector<uint8_t> zeros(D, 0);
#ifdef __AVX2__
  if (simd && D % 32 == 0) {
    const __m256i p1v = _mm256_set1_epi8(static_cast<char>(pen.p1));
    const __m256i p2v = _mm256_set1_epi8(static_cast<char>(pen.p2));
    walkRowBothWays(cost, cols, D, zeros.data(), forward, backward,
                    [&](const uint8_t* c, const uint8_t* prev, uint8_t prev_min, uint8_t* out) {
                      return stepAvx2(c, prev, prev_min, out, D, p1v, p2v);
                    });
    return;
  }
#elif defined(NERV_PATH_STEP_128)
  if (simd && D % 16 == 0) {
    const V16 p1v = splat16(static_cast<uint8_t>(pen.p1)), p2v = splat16(static_cast<uint8_t>(pen.p2));
    walkRowBothWays(cost, cols, D, zeros.data(), forward, backward,
                    [&](const uint8_t* c, const uint8_t* prev, uint8_t prev_min, uint8_t* out) {
                      return step128(c, prev, prev_min, out, D, p1v, p2v);
                    });
    return;
  }
#endif
  walkRowBothWays(cost, cols, D, zeros.data(), forward, backward,
                  [&](const uint8_t* c, const uint8_t* prev, uint8_t prev_min, uint8_t* out) {
                    return pathStepScalar(c, prev, prev_min, out, D, pen);
                  });
}

void aggregateRowVertical(const uint8_t* cost, const uint8_t* prev_row, const uint8_t* prev_min,
                          int cols, int D, PathPenalties pen, bool simd, uint8_t* out_row,
                          uint8_t* out_min, uint8_t* stream_row) {
  std::vector<uint8_t> zeros;
  if (!prev_row) zeros.assign(D, 0);
#ifdef __AVX2__
  if (simd && D % 32 == 0) {
    const __m256i p1v = _mm256_set1_epi8(static_cast<char>(pen.p1));
    const __m256i p2v = _mm256_set1_epi8(static_cast<char>(pen.p2));
    for (int x = 0; x < cols; ++x) {
      const size_t o = static_cast<size_t>(x) * D;
      uint8_t* stream = stream_row ? stream_row + o : nullptr;
      out_min[x] = prev_row ? stepAvx2(cost + o, prev_row + o, prev_min[x], out_row + o, D, p1v, p2v, stream)
                            : stepAvx2(cost + o, zeros.data(), 0, out_row + o, D, p1v, p2v, stream);
    }
    return;
  }
#endif
#if defined(NERV_PATH_STEP_128)
  if (simd && D % 16 == 0) {
    const V16 p1v = splat16(static_cast<uint8_t>(pen.p1)), p2v = splat16(static_cast<uint8_t>(pen.p2));
    for (int x = 0; x < cols; ++x) {
      const size_t o = static_cast<size_t>(x) * D;
      out_min[x] = prev_row ? step128(cost + o, prev_row + o, prev_min[x], out_row + o, D, p1v, p2v)
                            : step128(cost + o, zeros.data(), 0, out_row + o, D, p1v, p2v);
    }
  } else
#endif
  for (int x = 0; x < cols; ++x) {
    const size_t o = static_cast<size_t>(x) * D;
    out_min[x] = prev_row ? pathStepScalar(cost + o, prev_row + o, prev_min[x], out_row + o, D, pen)
                          : pathStepScalar(cost + o, zeros.data(), 0, out_row + o, D, pen);
  }
  if (stream_row) std::memcpy(stream_row, out_row, static_cast<size_t>(cols) * D);
}

}  // namespace nerv::stereo

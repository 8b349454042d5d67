// Unsigned byte vectors for the matcher's loops (path steps, winners), one struct per register
// width with the same members, so that a loop is written once as a template on it:
//   Bytes32: AVX2, 32 bytes a register;
//   Bytes16: SSE4.1 (x86) or NEON (ARM), 16 bytes a register.
// NERV_BYTES32 / NERV_BYTES16 say which of them this build has (an AVX2 build has both, so the
// unit tests check the 16-byte loops on it too). Every member is the plain byte operation its
// name says; none saturates unless it says so.
#pragma once

#include <cstdint>

#if defined(__AVX2__)
#include <immintrin.h>
#define NERV_BYTES32 1
#endif
#if defined(__ARM_NEON)
#include <arm_neon.h>
#define NERV_BYTES16 1
#elif defined(__SSE4_1__)
#include <smmintrin.h>
#define NERV_BYTES16 1
#endif

#define NERV_SIMD_INLINE __attribute__((always_inline)) inline

namespace nerv::stereo {

#ifdef NERV_BYTES32
struct Bytes32 {
  using V = __m256i;
  static constexpr int kLanes = 32;
  static constexpr const char* kName = "AVX2";
  static NERV_SIMD_INLINE V load(const uint8_t* p) { return _mm256_loadu_si256(reinterpret_cast<const V*>(p)); }
  static NERV_SIMD_INLINE void store(uint8_t* p, V v) { _mm256_storeu_si256(reinterpret_cast<V*>(p), v); }
  // p 32-byte aligned; a non-temporal store (it bypasses the cache)
  static NERV_SIMD_INLINE void stream(uint8_t* p, V v) { _mm256_stream_si256(reinterpret_cast<V*>(p), v); }
  static NERV_SIMD_INLINE V splat(uint8_t x) { return _mm256_set1_epi8(static_cast<char>(x)); }
  static NERV_SIMD_INLINE V lanes() {  // lane i holds i
    return _mm256_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
                            21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31);
  }
  static NERV_SIMD_INLINE V add(V a, V b) { return _mm256_add_epi8(a, b); }
  static NERV_SIMD_INLINE V sub(V a, V b) { return _mm256_sub_epi8(a, b); }
  static NERV_SIMD_INLINE V adds(V a, V b) { return _mm256_adds_epu8(a, b); }  // saturating
  static NERV_SIMD_INLINE V min(V a, V b) { return _mm256_min_epu8(a, b); }
  static NERV_SIMD_INLINE V max(V a, V b) { return _mm256_max_epu8(a, b); }
  static NERV_SIMD_INLINE V avg(V a, V b) { return _mm256_avg_epu8(a, b); }  // (a + b + 1) >> 1
  static NERV_SIMD_INLINE V eq(V a, V b) { return _mm256_cmpeq_epi8(a, b); }  // 255 where equal
  static NERV_SIMD_INLINE V bitOr(V a, V b) { return _mm256_or_si256(a, b); }
  static NERV_SIMD_INLINE V andNot(V a, V b) { return _mm256_andnot_si256(a, b); }  // ~a & b
  // mask lanes 255: b, lanes 0: a
  static NERV_SIMD_INLINE V select(V mask, V a, V b) { return _mm256_blendv_epi8(a, b, mask); }
  // lane i of the result = lane i - 1 of cur, lane 0 = the last lane of below
  static NERV_SIMD_INLINE V shiftUp(V below, V cur) {
    return _mm256_alignr_epi8(cur, _mm256_permute2x128_si256(below, cur, 0x21), 15);
  }
  // lane i of the result = lane i + 1 of cur, the last lane = lane 0 of above
  static NERV_SIMD_INLINE V shiftDown(V cur, V above) {
    return _mm256_alignr_epi8(_mm256_permute2x128_si256(cur, above, 0x21), cur, 1);
  }
  static NERV_SIMD_INLINE uint8_t minLane(V v) {  // fold to 16, pair bytes into 16-bit lanes, minpos
    __m128i x = _mm_min_epu8(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
    x = _mm_min_epu8(x, _mm_srli_epi16(x, 8));
    return static_cast<uint8_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(x)));
  }
  // the first lane equal to x, kLanes when there is none
  static NERV_SIMD_INLINE int firstEqual(V v, V x) {
    const unsigned mask = static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(v, x)));
    return mask ? __builtin_ctz(mask) : kLanes;
  }
  static NERV_SIMD_INLINE uint8_t lastLane(V v) { return static_cast<uint8_t>(_mm256_extract_epi8(v, 31)); }
};
#endif

#ifdef NERV_BYTES16
struct Bytes16 {
  static constexpr int kLanes = 16;
#if defined(__ARM_NEON)
  using V = uint8x16_t;
  static constexpr const char* kName = "NEON";
  static NERV_SIMD_INLINE V load(const uint8_t* p) { return vld1q_u8(p); }
  static NERV_SIMD_INLINE void store(uint8_t* p, V v) { vst1q_u8(p, v); }
  static NERV_SIMD_INLINE void stream(uint8_t* p, V v) { vst1q_u8(p, v); }  // NEON has no such hint
  static NERV_SIMD_INLINE V splat(uint8_t x) { return vdupq_n_u8(x); }
  static NERV_SIMD_INLINE V lanes() {
    static const uint8_t k[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    return vld1q_u8(k);
  }
  static NERV_SIMD_INLINE V add(V a, V b) { return vaddq_u8(a, b); }
  static NERV_SIMD_INLINE V sub(V a, V b) { return vsubq_u8(a, b); }
  static NERV_SIMD_INLINE V adds(V a, V b) { return vqaddq_u8(a, b); }
  static NERV_SIMD_INLINE V min(V a, V b) { return vminq_u8(a, b); }
  static NERV_SIMD_INLINE V max(V a, V b) { return vmaxq_u8(a, b); }
  static NERV_SIMD_INLINE V avg(V a, V b) { return vrhaddq_u8(a, b); }
  static NERV_SIMD_INLINE V eq(V a, V b) { return vceqq_u8(a, b); }
  static NERV_SIMD_INLINE V bitOr(V a, V b) { return vorrq_u8(a, b); }
  static NERV_SIMD_INLINE V andNot(V a, V b) { return vbicq_u8(b, a); }
  static NERV_SIMD_INLINE V select(V mask, V a, V b) { return vbslq_u8(mask, b, a); }
  static NERV_SIMD_INLINE V shiftUp(V below, V cur) { return vextq_u8(below, cur, 15); }
  static NERV_SIMD_INLINE V shiftDown(V cur, V above) { return vextq_u8(cur, above, 1); }
  static NERV_SIMD_INLINE uint8_t minLane(V v) { return vminvq_u8(v); }
  static NERV_SIMD_INLINE int firstEqual(V v, V x) {  // unequal lanes read 255, equal ones their index
    const uint8_t first = vminvq_u8(vorrq_u8(lanes(), vmvnq_u8(vceqq_u8(v, x))));
    return first == 255 ? kLanes : first;
  }
  static NERV_SIMD_INLINE uint8_t lastLane(V v) { return vgetq_lane_u8(v, 15); }
#else
  using V = __m128i;
  static constexpr const char* kName = "SSE4.1";
  static NERV_SIMD_INLINE V load(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const V*>(p)); }
  static NERV_SIMD_INLINE void store(uint8_t* p, V v) { _mm_storeu_si128(reinterpret_cast<V*>(p), v); }
  // p 16-byte aligned
  static NERV_SIMD_INLINE void stream(uint8_t* p, V v) { _mm_stream_si128(reinterpret_cast<V*>(p), v); }
  static NERV_SIMD_INLINE V splat(uint8_t x) { return _mm_set1_epi8(static_cast<char>(x)); }
  static NERV_SIMD_INLINE V lanes() { return _mm_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15); }
  static NERV_SIMD_INLINE V add(V a, V b) { return _mm_add_epi8(a, b); }
  static NERV_SIMD_INLINE V sub(V a, V b) { return _mm_sub_epi8(a, b); }
  static NERV_SIMD_INLINE V adds(V a, V b) { return _mm_adds_epu8(a, b); }
  static NERV_SIMD_INLINE V min(V a, V b) { return _mm_min_epu8(a, b); }
  static NERV_SIMD_INLINE V max(V a, V b) { return _mm_max_epu8(a, b); }
  static NERV_SIMD_INLINE V avg(V a, V b) { return _mm_avg_epu8(a, b); }
  static NERV_SIMD_INLINE V eq(V a, V b) { return _mm_cmpeq_epi8(a, b); }
  static NERV_SIMD_INLINE V bitOr(V a, V b) { return _mm_or_si128(a, b); }
  static NERV_SIMD_INLINE V andNot(V a, V b) { return _mm_andnot_si128(a, b); }
  static NERV_SIMD_INLINE V select(V mask, V a, V b) { return _mm_blendv_epi8(a, b, mask); }
  static NERV_SIMD_INLINE V shiftUp(V below, V cur) { return _mm_alignr_epi8(cur, below, 15); }
  static NERV_SIMD_INLINE V shiftDown(V cur, V above) { return _mm_alignr_epi8(above, cur, 1); }
  static NERV_SIMD_INLINE uint8_t minLane(V v) {
    return static_cast<uint8_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(_mm_min_epu8(v, _mm_srli_epi16(v, 8)))));
  }
  static NERV_SIMD_INLINE int firstEqual(V v, V x) {
    const unsigned mask = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, x)));
    return mask ? __builtin_ctz(mask) : kLanes;
  }
  static NERV_SIMD_INLINE uint8_t lastLane(V v) { return static_cast<uint8_t>(_mm_extract_epi8(v, 15)); }
#endif
};
#endif

// The widest registers of this build: "AVX2", "SSE4.1", "NEON", or "portable loops" without any.
inline const char* widestBytesName() {
#if defined(NERV_BYTES32)
  return Bytes32::kName;
#elif defined(NERV_BYTES16)
  return Bytes16::kName;
#else
  return "portable loops";
#endif
}

}  // namespace nerv::stereo

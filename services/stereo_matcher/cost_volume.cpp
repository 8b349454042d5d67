#include "cost_volume.hpp"

#include <algorithm>

#if defined(__SSE4_1__)
#include <immintrin.h>
#endif
#if defined(__ARM_NEON)
#include <arm_neon.h>
#endif

namespace nerv::stereo {

void reverseCensusRow(const uint32_t* right, int cols, int min_disparity, int num_disparities,
                      uint32_t* reversed) {
  std::reverse_copy(right, right + cols, reversed);
  std::fill(reversed + cols, reversed + cols + min_disparity + num_disparities, right[0]);
}

namespace {

// The walk every vector loop shares: each column's D costs, `Step` at a time by `block`
// (block(l, r, c) writes the Step costs of code l against r[0..Step) to c), the rest one
// by one. The plain loop below stays a loop of its own: GCC vectorises it on vpopcntd.
template <int Step, typename Block>
inline void costWalk(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                     int min_disparity, int num_disparities, uint8_t* out, Block block) {
  const int vector_end = num_disparities - num_disparities % Step;
  for (int x = x0; x < x1; ++x) {
    const uint32_t l = left[x];
    const uint32_t* r = right_reversed + (cols - 1 - x) + min_disparity;
    uint8_t* c = out + static_cast<size_t>(x - x0) * num_disparities;
    int d = 0;
    for (; d < vector_end; d += Step) block(l, r + d, c + d);
    for (; d < num_disparities; ++d) c[d] = static_cast<uint8_t>(__builtin_popcount(l ^ r[d]));
  }
}

}  // namespace

void censusCostRangeScalar(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                           int min_disparity, int num_disparities, uint8_t* out) {
  for (int x = x0; x < x1; ++x) {
    const uint32_t l = left[x];
    const uint32_t* r = right_reversed + (cols - 1 - x) + min_disparity;
    uint8_t* c = out + static_cast<size_t>(x - x0) * num_disparities;
    for (int d = 0; d < num_disparities; ++d)
      c[d] = static_cast<uint8_t>(__builtin_popcount(l ^ r[d]));
  }
}

#if defined(__AVX2__)
namespace {

// The popcount of each 32-bit lane: nibble counts by table lookup (pshufb), their bytes
// summed in pairs (maddubs) and the pairs per lane (madd).
inline __m256i popcountLanes(__m256i x) {
  const __m256i table = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4,
                                         0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
  const __m256i nibble = _mm256_set1_epi8(0x0f);
  const __m256i bytes = _mm256_add_epi8(_mm256_shuffle_epi8(table, _mm256_and_si256(x, nibble)),
                                        _mm256_shuffle_epi8(table, _mm256_and_si256(_mm256_srli_epi16(x, 4), nibble)));
  return _mm256_madd_epi16(_mm256_maddubs_epi16(bytes, _mm256_set1_epi8(1)), _mm256_set1_epi16(1));
}

}  // namespace

void censusCostRangeAvx2(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                         int min_disparity, int num_disparities, uint8_t* out) {
  // packus works per 128-bit half: the 32 bytes come out as dwords a0-3 b0-3 c0-3 e0-3 |
  // a4-7 b4-7 c4-7 e4-7, put back in disparity order by one dword permute.
  const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  costWalk<32>(left, right_reversed, cols, x0, x1, min_disparity, num_disparities, out,
               [&](uint32_t l, const uint32_t* r, uint8_t* c) {
                 const __m256i lv = _mm256_set1_epi32(static_cast<int>(l));
                 auto lanes = [&](int k) {
                   return popcountLanes(_mm256_xor_si256(lv, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(r + k))));
                 };
                 const __m256i ab = _mm256_packus_epi32(lanes(0), lanes(8));
                 const __m256i ce = _mm256_packus_epi32(lanes(16), lanes(24));
                 const __m256i bytes = _mm256_permutevar8x32_epi32(_mm256_packus_epi16(ab, ce), order);
                 _mm256_storeu_si256(reinterpret_cast<__m256i*>(c), bytes);
               });
}
#endif

#if defined(__SSE4_1__)
void censusCostRangeSse41(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                          int min_disparity, int num_disparities, uint8_t* out) {
  // The AVX2 loop's steps on 16 bytes (SSSE3 pshufb and maddubs, SSE4.1 packus_epi32);
  // here packus keeps the order, so nothing is permuted.
  const __m128i table = _mm_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
  const __m128i nibble = _mm_set1_epi8(0x0f), ones8 = _mm_set1_epi8(1), ones16 = _mm_set1_epi16(1);
  costWalk<16>(left, right_reversed, cols, x0, x1, min_disparity, num_disparities, out,
               [&](uint32_t l, const uint32_t* r, uint8_t* c) {
                 const __m128i lv = _mm_set1_epi32(static_cast<int>(l));
                 auto lanes = [&](int k) {
                   const __m128i v = _mm_xor_si128(lv, _mm_loadu_si128(reinterpret_cast<const __m128i*>(r + k)));
                   const __m128i bytes = _mm_add_epi8(_mm_shuffle_epi8(table, _mm_and_si128(v, nibble)),
                                                      _mm_shuffle_epi8(table, _mm_and_si128(_mm_srli_epi16(v, 4), nibble)));
                   return _mm_madd_epi16(_mm_maddubs_epi16(bytes, ones8), ones16);
                 };
                 const __m128i packed =
                     _mm_packus_epi16(_mm_packus_epi32(lanes(0), lanes(4)), _mm_packus_epi32(lanes(8), lanes(12)));
                 _mm_storeu_si128(reinterpret_cast<__m128i*>(c), packed);
               });
}
#endif


#if defined(__ARM_NEON)
void censusCostRangeNeon(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                         int min_disparity, int num_disparities, uint8_t* out) {
  // 16 costs a step: the count of each byte (cnt), then adjacent bytes summed twice
  // (pairwise add across two registers), which leaves each code's four bytes summed, in order.
  costWalk<16>(left, right_reversed, cols, x0, x1, min_disparity, num_disparities, out,
               [](uint32_t l, const uint32_t* r, uint8_t* c) {
                 const uint32x4_t lv = vdupq_n_u32(l);
                 auto bytes = [&](int k) { return vcntq_u8(vreinterpretq_u8_u32(veorq_u32(lv, vld1q_u32(r + k)))); };
                 const uint8x16_t ab = vpaddq_u8(bytes(0), bytes(4)), ce = vpaddq_u8(bytes(8), bytes(12));
                 vst1q_u8(c, vpaddq_u8(ab, ce));
               });
}
#endif

// The loop this build runs and its name, chosen once for both.
namespace {
struct ChosenCostLoop {
  CensusCostLoop loop;
  const char* name;
};
#if defined(__AVX2__) && !defined(__AVX512VPOPCNTDQ__)
constexpr ChosenCostLoop kCostLoop = {censusCostRangeAvx2, "AVX2"};
#elif defined(__SSE4_1__) && !defined(__AVX2__)
constexpr ChosenCostLoop kCostLoop = {censusCostRangeSse41, "SSE4.1"};
#elif defined(__ARM_NEON)
constexpr ChosenCostLoop kCostLoop = {censusCostRangeNeon, "NEON"};
#elif defined(__AVX512VPOPCNTDQ__)
// With AVX-512 VPOPCNTDQ the compiler vectorises the plain loop on vpopcntd itself.
constexpr ChosenCostLoop kCostLoop = {censusCostRangeScalar, "AVX-512 VPOPCNTDQ"};
#else
constexpr ChosenCostLoop kCostLoop = {censusCostRangeScalar, "portable loop"};
#endif
}  // namespace

const char* censusCostPath() { return kCostLoop.name; }

void censusCostRange(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                     int min_disparity, int num_disparities, uint8_t* out) {
  kCostLoop.loop(left, right_reversed, cols, x0, x1, min_disparity, num_disparities, out);
}

}  // namespace nerv::stereo

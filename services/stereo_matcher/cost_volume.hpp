// Matching cost of the own SGM: Hamming distance between census codes,
// C(x, y, d) = popcount(censusL(x, y) ^ censusR(x - min_disparity - d, y)),
// d in [0, D). One byte per cost, layout [y][x][d] so a pixel's D costs are
// contiguous (what the SIMD path aggregation loads). Right pixels left of the
// image reuse column 0. Costs are computed per row when a pass needs them
// (from the census codes, which stay in cache) rather than stored as a volume:
// recomputing is cheaper than the memory traffic of a W x H x D volume.
#pragma once

#include <cstdint>

namespace nerv::stereo {

// The right census row reversed and padded, reversed[j] = right[cols - 1 - j]
// for j < cols and right[0] after (cols + min_disparity + D entries): the D
// right codes a left pixel x is compared with then start at
// j = cols - 1 - x + min_disparity, contiguous and in disparity order, so the
// cost loop vectorises (XOR + popcount + narrow).
void reverseCensusRow(const uint32_t* right, int cols, int min_disparity, int num_disparities,
                      uint32_t* reversed);

// Costs of columns [x0, x1) of one row: out has (x1 - x0) * D bytes. Runs
// censusCostRangeAvx2 on a CPU target with AVX2 but without AVX-512 VPOPCNTDQ (most
// vehicle computers, and any package built for x86-64-v3), censusCostRangeSse41 on one
// with SSE4.1 but without AVX2, censusCostRangeNeon on ARM, else the plain loop, which
// the compiler vectorises on vpopcntd where it has it and leaves scalar where not: the
// plain loop on an AVX2 target took the matcher from 24 to 57 ms a KITTI frame.
void censusCostRange(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                     int min_disparity, int num_disparities, uint8_t* out);

// Which of the loops below censusCostRange runs in this build.
const char* censusCostPath();

// The signature every cost loop below shares (that of censusCostRange).
using CensusCostLoop = void (*)(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0,
                                int x1, int min_disparity, int num_disparities, uint8_t* out);

// The plain loop, and the AVX2 one (32 costs at a time: a nibble table per byte, bytes
// summed per lane, packed to bytes), which give the same bytes.
void censusCostRangeScalar(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                           int min_disparity, int num_disparities, uint8_t* out);
#if defined(__AVX2__)
void censusCostRangeAvx2(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                         int min_disparity, int num_disparities, uint8_t* out);
#endif
// The same on 16 bytes, for targets without AVX2 (x86-64-v2: SSSE3 and SSE4.1).
#if defined(__SSE4_1__)
void censusCostRangeSse41(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                          int min_disparity, int num_disparities, uint8_t* out);
#endif
// And on ARM (NEON: Jetson-class vehicle computers), where GCC leaves the plain loop scalar.
#if defined(__ARM_NEON)
void censusCostRangeNeon(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                         int min_disparity, int num_disparities, uint8_t* out);
#endif

}  // namespace nerv::stereo

// Matching cost volume of the own SGM: Hamming distance between census codes,
// C(x, y, d) = popcount(censusL(x, y) ^ censusR(x - min_disparity - d, y)),
// d in [0, D). One byte per cost, layout [y][x][d] so a pixel's D costs are
// contiguous (what the SIMD path aggregation loads). Right pixels left of the
// image reuse column 0.
#pragma once

#include <cstdint>
#include <vector>

namespace nerv::stereo {

// One row: out has cols * D bytes. scratch is reused between calls.
void censusCostRow(const uint64_t* left, const uint64_t* right, int cols, int min_disparity,
                   int num_disparities, uint8_t* out, std::vector<uint64_t>& scratch);

}  // namespace nerv::stereo

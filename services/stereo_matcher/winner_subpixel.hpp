// Winner-takes-all on the aggregated cost of one row, with uniqueness test,
// confidence and equiangular subpixel refinement, for the left view and
// (along the cost's diagonals) for the right view used by the left-right check.
//
// The winners work on S'(x, d) = avg(avg(L1, L2), avg(L3, L4)) of the four
// path costs (avg = (a + b + 1) >> 1, as the SIMD pavgb): one byte per
// disparity, so 32 disparities per AVX2 instruction. Measured on KITTI 2015
// 000005, the synthetic urban set and Middlebury Aloe, D1 / bad-2.0 moved by
// less than 0.05 points against the exact 16-bit sum. The subpixel fit uses
// the exact sum L1 + L2 + L3 + L4 at d - 1, d, d + 1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nerv::stereo {

// Equiangular ("V") fit through (-1, a), (0, b), (1, c) with b the minimum:
// offset of the true minimum in [-0.5, 0.5] (Shimizu & Okutomi 2005). For
// census costs, which grow about linearly away from the match, it is less
// biased toward integers than a parabola.
float equiangularOffset(int a, int b, int c);

struct WinnerOptions {
  int uniqueness_ratio = 10;  // [%]; 0 disables the test
  bool subpixel = true;
};

// out[k] = avg(avg(p0[k], p1[k]), avg(p2[k], p3[k])) for k < n.
void averagePaths(const uint8_t* const paths[4], size_t n, uint8_t* out);

// S: cols * D averaged costs ([x][d]). For every x: best[x] = first d of the
// minimum (-1 when the uniqueness test fails), disparity[x] = best (index
// units, -1 when invalid), confidence[x] = (S2 - S1) / S2 with S1 the minimum
// and S2 the best cost with |d - best| > 1 (0 when invalid).
void selectLeftWinners(const uint8_t* S, int cols, int num_disparities, WinnerOptions options,
                       int16_t* best, float* disparity, float* confidence);

// Right view: for right pixel xr the candidates are S(xr + min_disparity + d, d).
// best_right[xr] = first d of the minimum (-1 when no candidate lies in the image).
void selectRightWinners(const uint8_t* S, int cols, int num_disparities, int min_disparity,
                        int16_t* best_right, std::vector<uint8_t>& scratch_cost,
                        std::vector<int16_t>& scratch_index);

// disparity[x] += equiangular offset of the exact path sum around best[x]
// (where 0 < best[x] < D - 1).
void refineSubpixel(const uint8_t* const paths[4], int cols, int num_disparities,
                    const int16_t* best, float* disparity);

// All of the above for one row from the four path rows (cols * D bytes each),
// fused into one vector loop per pixel when D < 256 fills whole registers (the averaged costs
// never leave L1): AVX2 for D % 32 == 0, else SSE4.1 or NEON for D % 16 == 0; otherwise the
// separate steps. best_right may be nullptr (no left-right check). Identical results either way.
void selectWinnersFromPaths(const uint8_t* const paths[4], int cols, int num_disparities,
                            int min_disparity, WinnerOptions options, int16_t* best,
                            float* disparity, float* confidence, int16_t* best_right,
                            std::vector<uint8_t>& scratch_sum, std::vector<uint8_t>& scratch_cost,
                            std::vector<int16_t>& scratch_index);

// The fused loop on 16-byte registers (SSE4.1 or NEON) alone, which an AVX2 build takes only
// where D is an odd multiple of 16: for the tests. False, with nothing written, where the build
// has no 16-byte registers or D is not a multiple of 16 below 256.
bool selectWinnersFromPaths16(const uint8_t* const paths[4], int cols, int num_disparities,
                              int min_disparity, WinnerOptions options, int16_t* best,
                              float* disparity, float* confidence, int16_t* best_right);

// The registers of the fused loop of this build for D % 32 == 0: "AVX2", "SSE4.1", "NEON",
// or "portable loops".
const char* winnerPath();

}  // namespace nerv::stereo

// Winner-takes-all on the aggregated cost S(x, d) of one row, with uniqueness
// test, confidence and equiangular subpixel refinement, for the left view and
// (along the cost's diagonals) for the right view used by the left-right check.
#pragma once

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

// S: cols * D costs ([x][d]). For every x: best[x] = first d of the minimum
// (-1 when the uniqueness test fails), disparity[x] = best + subpixel offset
// (index units, -1 when invalid), confidence[x] = (S2 - S1) / S2 with S1 the
// minimum and S2 the best cost with |d - best| > 1 (0 when invalid). S is
// written to while a pixel is examined (three costs masked, then restored).
void selectLeftWinners(uint16_t* S, int cols, int num_disparities, WinnerOptions options,
                       int16_t* best, float* disparity, float* confidence);

// Right view: for right pixel xr the candidates are S(xr + min_disparity + d, d).
// best_right[xr] = first d of the minimum (-1 when no candidate lies in the image).
// Scratch vectors are reused between rows.
void selectRightWinners(const uint16_t* S, int cols, int num_disparities, int min_disparity,
                        int16_t* best_right, std::vector<uint16_t>& scratch_cost,
                        std::vector<int16_t>& scratch_index);

// Fused AVX2 form of "S = sum of the four path costs, then both winner
// selections" for num_disparities % 32 == 0 (falls back to the separate steps
// otherwise): S never leaves L1. paths: four cols * D byte rows. best_right may
// be nullptr (no left-right check). Results identical to the separate steps.
void selectWinnersFromPaths(const uint8_t* const paths[4], int cols, int num_disparities,
                            int min_disparity, WinnerOptions options, int16_t* best,
                            float* disparity, float* confidence, int16_t* best_right,
                            std::vector<uint16_t>& scratch_sum, std::vector<uint16_t>& scratch_cost,
                            std::vector<int16_t>& scratch_index);

}  // namespace nerv::stereo

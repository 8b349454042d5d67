// Semi-global cost aggregation along one path direction (Hirschmueller 2008,
// eq. 13): for the pixel p after p - r on the path,
//   L(p, d) = C(p, d) + min(L(p-r, d), L(p-r, d-1) + P1, L(p-r, d+1) + P1,
//                           min_k L(p-r, k) + P2) - min_k L(p-r, k).
// Subtracting the previous minimum bounds L by max C + P2, so with census
// costs (<= 32 bits) and P2 <= 255 - max C every value fits one byte and the SIMD
// path works on 32 disparities per AVX2 instruction with saturating uint8
// adds — and stays exact (checked against the scalar code and a reference).
#pragma once

#include <cstdint>

namespace nerv::stereo {

struct PathPenalties {
  int p1 = 10;
  int p2 = 120;
};

// True when this build has a vector step: AVX2 (32 disparities a register), or one on 16:
// NEON (ARM) or SSE4.1 (x86-64-v2; an AVX2 build takes it where D is an odd multiple of 16).
// pathStepPath() names the widest: "AVX2", "SSE4.1", "NEON" or "portable loops".
bool pathSimdAvailable();
const char* pathStepPath();

// One step for one pixel: prev = L(p - r, .) (all zeros and prev_min 0 at the
// start of a path, which gives L = C), out = L(p, .). Returns min_d out[d].
uint8_t pathStepScalar(const uint8_t* cost, const uint8_t* prev, uint8_t prev_min, uint8_t* out,
                       int num_disparities, PathPenalties pen);
// Same with the build's widest vector step that num_disparities fills (% 32 == 0 for AVX2,
// % 16 for NEON or SSE4.1); the scalar step otherwise.
uint8_t pathStepSimd(const uint8_t* cost, const uint8_t* prev, uint8_t prev_min, uint8_t* out,
                     int num_disparities, PathPenalties pen);

// Left-to-right and right-to-left paths of one image row. cost, forward and
// backward hold cols * D bytes ([x][d]). simd: use the vector step where D fills its
// registers (as pathStepSimd).
void aggregateRowHorizontal(const uint8_t* cost, int cols, int num_disparities, PathPenalties pen,
                            bool simd, uint8_t* forward, uint8_t* backward);

// One row of a vertical path: prev_row / prev_min are the previous row's L and
// per-pixel minima along the path (nullptr for the first row of the path).
// stream_row (optional, 32-byte aligned for the SIMD path): a second copy of
// out_row written with non-temporal stores (see streaming_store.hpp).
void aggregateRowVertical(const uint8_t* cost, const uint8_t* prev_row, const uint8_t* prev_min,
                          int cols, int num_disparities, PathPenalties pen, bool simd,
                          uint8_t* out_row, uint8_t* out_min, uint8_t* stream_row = nullptr);

}  // namespace nerv::stereo

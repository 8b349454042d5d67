#include "path_aggregation.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "simd_bytes.hpp"

namespace nerv::stereo {

namespace {

// The vector step on B::kLanes disparities a register (B: simd_bytes.hpp; 32 with AVX2, 16
// with SSE4.1 or NEON). D % B::kLanes == 0. The D costs of the previous pixel sit in
// D / kLanes registers; the d - 1 / d + 1 neighbours are the register shifted by one byte
// (across the 128-bit lanes for AVX2), with 255 shifted in at both ends.
// stream (aligned to the register, or nullptr): a second copy of out written with
// non-temporal stores (the vertical paths' checkpoints).
template <class B>
NERV_SIMD_INLINE uint8_t stepBytes(const uint8_t* cost, const uint8_t* prev, uint8_t prev_min,
                                   uint8_t* out, int D, typename B::V p1v, typename B::V p2v,
                                   uint8_t* stream = nullptr) {
  using V = typename B::V;
  constexpr int N = B::kLanes;
  const V minv = B::splat(prev_min);
  const V jump = B::adds(minv, p2v);
  const V full = B::splat(255);
  V below = full, cur = B::load(prev), running = full;
  for (int k = 0; k < D; k += N) {
    const V above = k + N < D ? B::load(prev + k + N) : full;
    const V m = B::min(B::min(cur, B::adds(B::shiftUp(below, cur), p1v)),     // L(d - 1) + P1
                       B::min(B::adds(B::shiftDown(cur, above), p1v), jump)); // L(d + 1) + P1
    const V v = B::adds(B::sub(m, minv), B::load(cost + k));
    B::store(out + k, v);
    if (stream) B::stream(stream + k, v);
    running = B::min(running, v);
    below = cur;
    cur = above;
  }
  return B::minLane(running);
}

// Calls body(B{}, p1v, p2v) with the widest byte vector B of this build whose register D fills
// (32 lanes with AVX2, else 16 with SSE4.1 or NEON; an AVX2 build also takes the 16-byte step
// for D = 16, 48, ...; the 16-byte step is the AVX2 step's arithmetic, register for register:
// stereoSgm.PathStepSimdEqualsScalar) and the penalties splat into B's registers. False,
// without calling it, when there is none or simd is off.
template <class Body>
NERV_SIMD_INLINE bool withStepBytes(int D, bool simd, PathPenalties pen, Body&& body) {
  if (!simd) return false;
  auto run = [&](auto bytes) {
    using B = decltype(bytes);
    body(bytes, B::splat(static_cast<uint8_t>(pen.p1)), B::splat(static_cast<uint8_t>(pen.p2)));
    return true;
  };
#ifdef NERV_BYTES32
  if (D % Bytes32::kLanes == 0) return run(Bytes32{});
#endif
#ifdef NERV_BYTES16
  if (D % Bytes16::kLanes == 0) return run(Bytes16{});
#endif
  (void)D;
  (void)run;
  return false;
}

}  // namespace

bool pathSimdAvailable() {
#if defined(NERV_BYTES32) || defined(NERV_BYTES16)
  return true;
#else
  return false;
#endif
}

const char* pathStepPath() { return widestBytesName(); }

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
  uint8_t least = 0;
  const bool vector = withStepBytes(D, true, pen, [&](auto bytes, auto p1v, auto p2v) {
    least = stepBytes<decltype(bytes)>(cost, prev, prev_min, out, D, p1v, p2v);
  });
  return vector ? least : pathStepScalar(cost, prev, prev_min, out, D, pen);
}

namespace {
// Both directions of a row in one loop: two independent dependency chains per iteration
// keep the core busy while each waits on its horizontal minimum. step(cost, prev, prev_min,
// out) is one of the steps above.
template <class Step>
NERV_SIMD_INLINE void walkRowBothWays(const uint8_t* cost, int cols, int D, const uint8_t* zeros,
                                      uint8_t* forward, uint8_t* backward, Step step) {
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

// One row of a vertical path, pixel by pixel: step(offset, prev, prev_min) for each pixel,
// from the previous row or, at a path's start, from zeros.
template <class Step>
NERV_SIMD_INLINE void walkRowDown(const uint8_t* prev_row, const uint8_t* prev_min, int cols, int D,
                                  uint8_t* out_min, Step step) {
  std::vector<uint8_t> zeros;
  if (!prev_row) zeros.assign(D, 0);
  for (int x = 0; x < cols; ++x) {
    const size_t o = static_cast<size_t>(x) * D;
    out_min[x] = prev_row ? step(o, prev_row + o, prev_min[x]) : step(o, zeros.data(), uint8_t{0});
  }
}
}  // namespace

void aggregateRowHorizontal(const uint8_t* cost, int cols, int D, PathPenalties pen, bool simd,
                            uint8_t* forward, uint8_t* backward) {
  if (cols <= 0) return;
  const std::vector<uint8_t> zeros(D, 0);
  const bool vector = withStepBytes(D, simd, pen, [&](auto bytes, auto p1v, auto p2v) {
    using B = decltype(bytes);
    walkRowBothWays(cost, cols, D, zeros.data(), forward, backward,
                    [&](const uint8_t* c, const uint8_t* prev, uint8_t prev_min, uint8_t* out) {
                      return stepBytes<B>(c, prev, prev_min, out, D, p1v, p2v);
                    });
  });
  if (vector) return;
  walkRowBothWays(cost, cols, D, zeros.data(), forward, backward,
                  [&](const uint8_t* c, const uint8_t* prev, uint8_t prev_min, uint8_t* out) {
                    return pathStepScalar(c, prev, prev_min, out, D, pen);
                  });
}

void aggregateRowVertical(const uint8_t* cost, const uint8_t* prev_row, const uint8_t* prev_min,
                          int cols, int D, PathPenalties pen, bool simd, uint8_t* out_row,
                          uint8_t* out_min, uint8_t* stream_row) {
  const bool vector = withStepBytes(D, simd, pen, [&](auto bytes, auto p1v, auto p2v) {
    using B = decltype(bytes);
    walkRowDown(prev_row, prev_min, cols, D, out_min, [&](size_t o, const uint8_t* prev, uint8_t least) {
      return stepBytes<B>(cost + o, prev, least, out_row + o, D, p1v, p2v, stream_row ? stream_row + o : nullptr);
    });
  });
  if (vector) return;
  walkRowDown(prev_row, prev_min, cols, D, out_min, [&](size_t o, const uint8_t* prev, uint8_t least) {
    return pathStepScalar(cost + o, prev, least, out_row + o, D, pen);
  });
  if (stream_row) std::memcpy(stream_row, out_row, static_cast<size_t>(cols) * D);
}

}  // namespace nerv::stereo

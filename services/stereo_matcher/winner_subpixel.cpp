#include "winner_subpixel.hpp"

#include <algorithm>
#include <cstdlib>

#include "simd_bytes.hpp"

namespace nerv::stereo {

float equiangularOffset(int a, int b, int c) {
  // Equal slopes on both sides: the steeper measured side gives the slope.
  const int slope = std::max(a - b, c - b);
  if (slope <= 0) return 0.0f;
  return std::clamp(0.5f * static_cast<float>(a - c) / static_cast<float>(slope), -0.5f, 0.5f);
}

void averagePaths(const uint8_t* const p[4], size_t n, uint8_t* out) {
  // Restrict-qualified copies, so GCC vectorises the loop on targets without AVX2 (the
  // rounded byte average is one instruction there too: pavgb, urhadd).
  const uint8_t* __restrict a = p[0];
  const uint8_t* __restrict b = p[1];
  const uint8_t* __restrict c = p[2];
  const uint8_t* __restrict e = p[3];
  uint8_t* __restrict o = out;
  for (size_t k = 0; k < n; ++k) {
    const uint8_t ab = static_cast<uint8_t>((a[k] + b[k] + 1) >> 1), ce = static_cast<uint8_t>((c[k] + e[k] + 1) >> 1);
    o[k] = static_cast<uint8_t>((ab + ce + 1) >> 1);
  }
}

namespace {

// Smallest cost with |d - d1| > 1 (s1 when there is none, D <= 3).
inline int secondBest(const uint8_t* s, int D, int d1, int s1) {
  int second = 256;
  for (int d = 0; d < D; ++d)
    if (d < d1 - 1 || d > d1 + 1) second = std::min(second, static_cast<int>(s[d]));
  return second == 256 ? s1 : second;
}

// Uniqueness test and confidence for one pixel.
inline void decide(int d1, int s1, int s2, WinnerOptions opt, int16_t& best, float& disparity,
                   float& confidence) {
  if (opt.uniqueness_ratio > 0 && s2 * (100 - opt.uniqueness_ratio) < s1 * 100) {
    best = -1;
    disparity = -1.0f;
    confidence = 0.0f;
    return;
  }
  best = static_cast<int16_t>(d1);
  disparity = static_cast<float>(d1);
  confidence = s2 > 0 ? static_cast<float>(s2 - s1) / static_cast<float>(s2) : 0.0f;
}

// Subpixel offset from the exact path sum at d1 - 1, d1, d1 + 1 (o: the
// pixel's offset in the path rows). The averaged minimum may sit a rounding
// step off the exact one: fit only when d1 is a minimum of the exact sum too.
inline void refinePixel(const uint8_t* const p[4], size_t o, int d1, float& disparity) {
  auto sum = [&](size_t k) { return p[0][k] + p[1][k] + p[2][k] + p[3][k]; };
  const size_t k = o + d1;
  const int a = sum(k - 1), b = sum(k), c = sum(k + 1);
  if (b <= a && b <= c) disparity = static_cast<float>(d1) + equiangularOffset(a, b, c);
}

// Fused per-pixel loop on the byte vectors B (simd_bytes.hpp): D = B::kLanes * NB, D < 256
// (byte indices, 255 = no candidate). NB registers per pixel: the right view's running
// minimum and the averaged costs stay in registers (the compiler unrolls the NB loops).
template <class B, int NB>
void fusedWinnersN(const uint8_t* const paths[4], int cols, int min_disparity, WinnerOptions opt,
                   int16_t* best, float* disparity, float* confidence, int16_t* best_right) {
  using V = typename B::V;
  constexpr int N = B::kLanes;
  constexpr int D = N * NB;
  static_assert(D < 256, "byte indices");
  // Right view without a scattered running minimum: the candidates (x, d) and
  // (x - 1, d - 1) see the same right pixel, so the best candidate so far per
  // right pixel is a D-vector shifted by one lane per left pixel:
  // run_x[d] = min(S(x, d), run_{x-1}[d - 1]); lane D - 1 is final then.
  const V full = B::splat(255);
  const V lanes = B::lanes();
  // lane i of register j: d = N j + i
  auto index = [&](int j) { return B::add(lanes, B::splat(static_cast<uint8_t>(N * j))); };
  V run_cost[NB], run_index[NB], v[NB];
  for (int j = 0; j < NB; ++j) run_cost[j] = run_index[j] = full;
  if (best_right) std::fill(best_right, best_right + cols, int16_t{-1});
  for (int x = 0; x < cols; ++x) {
    const size_t o = static_cast<size_t>(x) * D;
    V vmin = full;
    for (int j = 0; j < NB; ++j) {
      const int k = N * j;
      v[j] = B::avg(B::avg(B::load(paths[0] + o + k), B::load(paths[1] + o + k)),
                    B::avg(B::load(paths[2] + o + k), B::load(paths[3] + o + k)));
      vmin = B::min(vmin, v[j]);
    }
    if (best_right) {
      // from the top register down, so each shift reads the register below before it changes
      for (int j = NB - 1; j >= 0; --j) {
        const V below_cost = j > 0 ? run_cost[j - 1] : full;  // run_{x-1}[-1]: no candidate
        const V below_index = j > 0 ? run_index[j - 1] : full;
        const V shifted_cost = B::shiftUp(below_cost, run_cost[j]);
        const V shifted_index = B::shiftUp(below_index, run_index[j]);
        // keep the earlier (smaller d) candidate unless v is strictly smaller;
        // an empty lane (index 255) always takes v
        const V keep = B::andNot(B::eq(shifted_index, full), B::eq(B::max(v[j], shifted_cost), v[j]));
        run_cost[j] = B::select(keep, v[j], shifted_cost);
        run_index[j] = B::select(keep, index(j), shifted_index);
      }
      const int xr = x - min_disparity - (D - 1);  // its last candidate was (x, D - 1)
      if (xr >= 0) best_right[xr] = B::lastLane(run_index[NB - 1]);
    }
    const int s1 = B::minLane(vmin);
    const V target = B::splat(static_cast<uint8_t>(s1));
    int d1 = 0;
    for (int j = 0; j < NB; ++j) {
      const int lane = B::firstEqual(v[j], target);
      if (lane < N) {
        d1 = N * j + lane;
        break;
      }
    }
    // second best: lanes d1 - 1 .. d1 + 1 masked to 255 by an index compare
    const V lo = B::splat(static_cast<uint8_t>(d1 - 1));
    const V two = B::splat(2);
    V m2 = full;
    for (int j = 0; j < NB; ++j) {
      const V t = B::sub(index(j), lo);
      const V near = B::eq(B::min(t, two), t);  // 0 <= d' - (d1 - 1) <= 2
      m2 = B::min(m2, B::bitOr(v[j], near));
    }
    // all-255 except the masked lanes would read 255 here; the scalar
    // secondBest then also sees 255 (a real cost), so both agree
    const int s2 = D <= 3 ? s1 : B::minLane(m2);
    decide(d1, s1, s2, opt, best[x], disparity[x], confidence[x]);
    if (opt.subpixel && best[x] > 0 && best[x] + 1 < D) refinePixel(paths, o, d1, disparity[x]);
  }
  if (best_right) {  // right pixels whose candidates ended at the row's last pixel
    uint8_t last[D];
    for (int j = 0; j < NB; ++j) B::store(last + N * j, run_index[j]);
    for (int d = 0; d + 1 < D; ++d) {
      const int xr = cols - 1 - min_disparity - d;
      if (xr >= 0 && xr < cols) best_right[xr] = last[d] == 255 ? -1 : last[d];
    }
  }
}

// The fused loop for D = B::kLanes * NB with NB from 1 to kMaxNB; false for other D.
template <class B, int NB, int kMaxNB>
bool fusedWinners(const uint8_t* const paths[4], int cols, int D, int min_disparity,
                  WinnerOptions opt, int16_t* best, float* disparity, float* confidence,
                  int16_t* best_right) {
  if constexpr (NB > kMaxNB) {
    return false;
  } else {
    if (D == B::kLanes * NB) {
      fusedWinnersN<B, NB>(paths, cols, min_disparity, opt, best, disparity, confidence, best_right);
      return true;
    }
    return fusedWinners<B, NB + 1, kMaxNB>(paths, cols, D, min_disparity, opt, best, disparity,
                                           confidence, best_right);
  }
}

}  // namespace

void selectLeftWinners(const uint8_t* S, int cols, int D, WinnerOptions opt, int16_t* best,
                       float* disparity, float* confidence) {
  for (int x = 0; x < cols; ++x) {
    const uint8_t* s = S + static_cast<size_t>(x) * D;
    // The smallest cost (a reduction GCC vectorises without AVX2), then its first place.
    uint8_t least = 255;
    for (int d = 0; d < D; ++d) least = std::min(least, s[d]);
    int d1 = 0;
    while (s[d1] != least) ++d1;
    decide(d1, s[d1], secondBest(s, D, d1, s[d1]), opt, best[x], disparity[x], confidence[x]);
  }
}

void selectRightWinners(const uint8_t* S, int cols, int D, int min_disparity, int16_t* best_right,
                        std::vector<uint8_t>& cost, std::vector<int16_t>& index) {
  // Reversed right index j = cols - 1 - xr = (cols - 1 - x) + min_disparity + d.
  const int n = cols + min_disparity + D;
  cost.assign(n, 255);
  index.assign(n, -1);
  for (int x = 0; x < cols; ++x) {
    const uint8_t* s = S + static_cast<size_t>(x) * D;
    uint8_t* __restrict c = cost.data() + (cols - 1 - x) + min_disparity;
    int16_t* __restrict i = index.data() + (cols - 1 - x) + min_disparity;
    for (int d = 0; d < D; ++d) {
      // x grows with d for a fixed right pixel: strict < keeps the smallest d. In 16 bits
      // and without a branch, so that GCC vectorises it without AVX2.
      const int16_t sd = s[d], cd = c[d], id = i[d];
      const bool better = (id < 0) | (sd < cd);
      c[d] = static_cast<uint8_t>(better ? sd : cd);
      i[d] = better ? static_cast<int16_t>(d) : id;
    }
  }
  for (int xr = 0; xr < cols; ++xr) best_right[xr] = index[cols - 1 - xr];
}

void refineSubpixel(const uint8_t* const p[4], int cols, int D, const int16_t* best,
                    float* disparity) {
  for (int x = 0; x < cols; ++x)
    if (best[x] > 0 && best[x] + 1 < D) refinePixel(p, static_cast<size_t>(x) * D, best[x], disparity[x]);
}

const char* winnerPath() { return widestBytesName(); }

bool selectWinnersFromPaths16(const uint8_t* const paths[4], int cols, int D, int min_disparity,
                              WinnerOptions opt, int16_t* best, float* disparity, float* confidence,
                              int16_t* best_right) {
#ifdef NERV_BYTES16
  return fusedWinners<Bytes16, 1, 15>(paths, cols, D, min_disparity, opt, best, disparity, confidence,
                                      best_right);
#else
  (void)paths, (void)cols, (void)D, (void)min_disparity, (void)opt, (void)best, (void)disparity,
      (void)confidence, (void)best_right;
  return false;
#endif
}

void selectWinnersFromPaths(const uint8_t* const paths[4], int cols, int D, int min_disparity,
                            WinnerOptions opt, int16_t* best, float* disparity, float* confidence,
                            int16_t* best_right, std::vector<uint8_t>& sum,
                            std::vector<uint8_t>& cost, std::vector<int16_t>& index) {
  bool done = false;
#if defined(NERV_BYTES32)
  done = fusedWinners<Bytes32, 1, 7>(paths, cols, D, min_disparity, opt, best, disparity, confidence,
                                     best_right);
#endif
  if (!done) done = selectWinnersFromPaths16(paths, cols, D, min_disparity, opt, best, disparity,
                                             confidence, best_right);
  if (!done) {
    sum.resize(static_cast<size_t>(cols) * D);
    averagePaths(paths, sum.size(), sum.data());
    selectLeftWinners(sum.data(), cols, D, opt, best, disparity, confidence);
    if (best_right) selectRightWinners(sum.data(), cols, D, min_disparity, best_right, cost, index);
    if (opt.subpixel) refineSubpixel(paths, cols, D, best, disparity);
  }
}

}  // namespace nerv::stereo

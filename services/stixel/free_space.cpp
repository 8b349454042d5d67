#include "free_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#ifdef __AVX2__
#include <immintrin.h>
#endif

#include "v_disparity.hpp"

namespace nerv::stixel {

void obstacleDisparityWindow(const GroundModel& g, int rows, float ground_tolerance_m,
                             float max_height_m, std::vector<float>& lo,
                             std::vector<float>& hi) {
  // height = h*(d - dg)/d (ground_geometry.hpp) solved for d:
  //   height > tol   <=>  d > h*dg/(h - tol)                      (tol < h)
  //   height < Hmax  <=>  d*(h - Hmax) < h*dg
  const float h = g.height_m;
  const float inf = std::numeric_limits<float>::infinity();
  lo.assign(rows, 0.0f);
  hi.assign(rows, inf);
  for (int v = 0; v < rows; ++v) {
    const float dg = g.groundDisparity(static_cast<float>(v));
    float l = 0.0f, u = inf;
    if (ground_tolerance_m < h) {
      l = std::max(l, h * dg / (h - ground_tolerance_m));
    } else {
      l = inf;  // a camera below the tolerance sees nothing above it; degenerate config
    }
    if (max_height_m > h) {
      l = std::max(l, h * dg / (h - max_height_m));
    } else if (max_height_m < h) {
      u = h * dg / (h - max_height_m);
    } else if (dg <= 0) {
      u = 0.0f;
    }
    lo[v] = l;
    hi[v] = u;
  }
}

int obstacleHalfWindow(int k) {
  // An upright obstacle spreads over +-1 bin of quantisation; near ones also over
  // their own depth (bumper to windscreen), which grows with d^2.
  return 1 + k / 24;
}

OccupancyGrid buildOccupancy(const cv::Mat& disparity, const StereoCamera& cam,
                             const GroundModel& ground, const FreeSpaceParams& p) {
  OccupancyGrid grid;
  const int cw = std::max(1, p.column_width_px);
  grid.column_width_px = cw;
  grid.strips = (disparity.cols + cw - 1) / cw;
  grid.bins = std::max(1, static_cast<int>(std::ceil(p.max_disparity_px)));
  const float d_min = static_cast<float>(cam.disparityFromDepth(p.max_distance_m));
  grid.min_bin = std::clamp(static_cast<int>(d_min), 0, grid.bins - 1);

  std::vector<float> lo, hi;
  obstacleDisparityWindow(ground, disparity.rows, p.ground_tolerance_m,
                          p.max_height_above_ground_m, lo, hi);
  const size_t cells = static_cast<size_t>(grid.strips) * grid.bins;
  std::vector<int> count(cells, 0);
  std::vector<int> top(cells, disparity.rows);  // highest (smallest) row of the cell
  std::vector<int> bottom(cells, 0);            // lowest (largest) row of the cell
  int max_bin = -1;
  for (int v = 0; v < disparity.rows; ++v) {
    const float l = std::max(lo[v], d_min);
    const float u = std::min(hi[v], p.max_disparity_px);
    if (!(l < u)) continue;
    const float* row = disparity.ptr<float>(v);
    auto vote = [&](int x) {
      const int b = static_cast<int>(row[x]);
      max_bin = std::max(max_bin, b);
      const size_t i = static_cast<size_t>(x / cw) * grid.bins + b;
      ++count[i];
      top[i] = std::min(top[i], v);  // rows ascend: the first pixel sets it
      bottom[i] = v;                 // and the last one this
    };
    int x = 0;
#ifdef __AVX2__
    // Most pixels of a row are road or sky: eight are tested at once and only
    // the obstacle pixels among them vote, in column order.
    const __m256 v_l = _mm256_set1_ps(l), v_u = _mm256_set1_ps(u);
    for (; x + 8 <= disparity.cols; x += 8) {
      const __m256 d = _mm256_loadu_ps(row + x);
      unsigned m = static_cast<unsigned>(_mm256_movemask_ps(
          _mm256_and_ps(_mm256_cmp_ps(d, v_l, _CMP_GT_OQ), _mm256_cmp_ps(d, v_u, _CMP_LT_OQ))));
      for (; m; m &= m - 1) vote(x + __builtin_ctz(m));
    }
#endif
    for (; x < disparity.cols; ++x)
      if (row[x] > l && row[x] < u) vote(x);  // also drops NaN
  }
  // count pixels of a strip w px wide at disparity d span count/w rows, and a row
  // at depth Z = fx*B/d is Z/fy metres high: filled = count*fx*B/(w*fy*d).
  // The highest pixel at row v reaches h*(d - dg(v))/d over the road.
  grid.end_bin = std::max(grid.min_bin, max_bin + 1);
  grid.filled_m.assign(cells, 0.0f);
  grid.reach_m.assign(cells, 0.0f);
  grid.base_m.assign(cells, 0.0f);
  if (p.max_clearance_m > 0) grid.max_clearance_m = p.max_clearance_m;
  const double k = cam.fx * cam.baseline_m / cam.fy;
  for (int s = 0; s < grid.strips; ++s) {
    const int w = std::min(cw, disparity.cols - s * cw);
    for (int b = grid.min_bin; b < grid.end_bin; ++b) {
      const size_t i = grid.index(s, b);
      if (!count[i]) continue;
      const float d = b + 0.5f;
      grid.filled_m[i] = static_cast<float>(count[i] * k / (w * d));
      grid.reach_m[i] = ground.height_m * (d - ground.groundDisparity(static_cast<float>(top[i]))) / d;
      grid.base_m[i] = ground.height_m * (d - ground.groundDisparity(static_cast<float>(bottom[i]))) / d;
    }
  }
  return grid;
}

float obstacleScore(const OccupancyGrid& grid, int s, int k) {
  const int hw = obstacleHalfWindow(k);
  const int a = std::max(grid.min_bin, k - hw), b = std::min(grid.end_bin, k + hw + 1);
  float filled = 0, reach = 0, base = std::numeric_limits<float>::infinity();
  for (int j = a; j < b; ++j) {
    const size_t i = grid.index(s, j);
    if (grid.filled_m[i] <= 0) continue;
    filled += grid.filled_m[i];
    reach = std::max(reach, grid.reach_m[i]);
    base = std::min(base, grid.base_m[i]);
  }
  if (!(filled > 0) || base > grid.max_clearance_m) return 0.0f;
  return std::min(filled, reach - base);
}

std::vector<int> solveFreeSpace(const OccupancyGrid& grid, const FreeSpaceParams& p) {
  // States per strip: boundary at bin k in [min_bin, bins) or "free" (index n).
  // Data cost of k [m]: the strongest obstacle evidence nearer than k's window (it
  // would be driven through) plus kMissingWeight times the height k's own evidence
  // lacks to be an obstacle; "free" costs the strongest evidence of the strip. The
  // maximum, not the sum, of nearer evidence keeps diffuse clutter (lawn, kerbs)
  // from adding up. With kMissingWeight = 3 an isolated obstacle is chosen once its
  // score passes 3/4 of min_obstacle_height_m. Pairwise: smoothness_m per bin of
  // jump, capped at jump_cap_bins so depth discontinuities at object edges stay cheap.
  constexpr float kMissingWeight = 3.0f;
  const int k0 = grid.min_bin;
  const int n = grid.end_bin - k0;  // boundary states; state n = free
  std::vector<int> result(grid.strips, -1);
  if (grid.strips == 0 || n <= 0) return result;
  const float lambda = p.smoothness_m;
  const float cap = lambda * std::max(1, p.jump_cap_bins);
  const float h_min = p.min_obstacle_height_m;

  std::vector<float> cost(n + 1), prev(n + 1), env(n + 1), score(n), nearer(n + 1);
  std::vector<int> env_arg(n + 1);
  std::vector<int> back(static_cast<size_t>(grid.strips) * (n + 1));

  auto dataCost = [&](int s, std::vector<float>& c) {
    // Bins whose window holds no pixel score 0: only the strip's occupied span is scored.
    int first = grid.end_bin, last = -1;
    for (int k = k0; k < grid.end_bin; ++k)
      if (grid.filled_m[grid.index(s, k)] > 0) first = std::min(first, k), last = k;
    for (int i = 0; i < n; ++i) {
      const int k = i + k0, hw = obstacleHalfWindow(k);
      score[i] = k + hw < first || k - hw > last ? 0.0f : obstacleScore(grid, s, k);
    }
    nearer[n] = 0;  // nearer[i] = max score over bins >= i
    for (int i = n - 1; i >= 0; --i) nearer[i] = std::max(nearer[i + 1], score[i]);
    for (int i = 0; i < n; ++i) {
      const int hw = obstacleHalfWindow(i + k0);
      c[i] = nearer[std::min(n, i + hw + 1)] + kMissingWeight * std::max(0.0f, h_min - score[i]);
    }
    c[n] = nearer[0];
  };

  dataCost(0, prev);
  for (int s = 1; s < grid.strips; ++s) {
    // Lower envelope of prev[j] + lambda*|i - j| by two passes (distance transform).
    for (int i = 0; i < n; ++i) env[i] = prev[i], env_arg[i] = i;
    for (int i = 1; i < n; ++i)
      if (env[i - 1] + lambda < env[i]) env[i] = env[i - 1] + lambda, env_arg[i] = env_arg[i - 1];
    for (int i = n - 2; i >= 0; --i)
      if (env[i + 1] + lambda < env[i]) env[i] = env[i + 1] + lambda, env_arg[i] = env_arg[i + 1];
    int best = 0;
    for (int i = 1; i <= n; ++i)
      if (prev[i] < prev[best]) best = i;
    dataCost(s, cost);
    int* bk = &back[static_cast<size_t>(s) * (n + 1)];
    for (int i = 0; i < n; ++i) {
      float m = env[i];
      int arg = env_arg[i];
      if (prev[best] + cap < m) m = prev[best] + cap, arg = best;
      if (prev[n] + cap < m) m = prev[n] + cap, arg = n;
      cost[i] += m;
      bk[i] = arg;
    }
    // free -> free is free of charge; anything -> free pays the cap.
    float mf = prev[n];
    int af = n;
    if (prev[best] + cap < mf) mf = prev[best] + cap, af = best;
    cost[n] += mf;
    bk[n] = af;
    std::swap(prev, cost);
  }
  int state = 0;
  for (int i = 1; i <= n; ++i)
    if (prev[i] < prev[state]) state = i;
  for (int s = grid.strips - 1; s >= 0; --s) {
    result[s] = state == n ? -1 : state + k0;
    if (s > 0) state = back[static_cast<size_t>(s) * (n + 1) + state];
  }
  return result;
}

}  // namespace nerv::stixel

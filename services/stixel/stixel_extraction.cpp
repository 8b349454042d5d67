#include "stixel_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#ifdef __AVX2__
#include <immintrin.h>
#endif

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"
#include "obstacle_map.hpp"

namespace nerv::stixel {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// One row of a strip in the top search: valid pixels (a finite disparity above
// road_max), matches (within tol of d), misses, and misses that are no near
// miss (not in [near_lo, d)).
struct RowCounts {
  int matches = 0, valid = 0, misses = 0, far_misses = 0;
};

#ifdef __AVX2__
// The per-pixel tests of countRow on one register of eight columns (masked
// lanes load 0, which is no valid disparity), with the strip's constants set
// once: the same comparisons as the scalar loop in countRow.
struct LaneTest {
  __m256 d, tol, near_lo, zero = _mm256_setzero_ps(), inf = _mm256_set1_ps(kInf);
  __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  LaneTest(float d_, float tol_, float near_lo_)
      : d(_mm256_set1_ps(d_)), tol(_mm256_set1_ps(tol_)), near_lo(_mm256_set1_ps(near_lo_)) {}
  void add(RowCounts& c, __m256 x, float road_max) const {
    const __m256 ok = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(x, zero, _CMP_GT_OQ), _mm256_cmp_ps(x, inf, _CMP_LT_OQ)),
                                    _mm256_cmp_ps(x, _mm256_set1_ps(road_max), _CMP_GT_OQ));
    const __m256 close = _mm256_cmp_ps(_mm256_and_ps(_mm256_sub_ps(x, d), abs_mask), tol, _CMP_LE_OQ);
    const __m256 near = _mm256_and_ps(_mm256_cmp_ps(x, d, _CMP_LT_OQ), _mm256_cmp_ps(x, near_lo, _CMP_GE_OQ));
    const int valid = __builtin_popcount(_mm256_movemask_ps(ok));
    const int matches = __builtin_popcount(_mm256_movemask_ps(_mm256_and_ps(ok, close)));
    c.valid += valid;
    c.matches += matches;
    c.misses += valid - matches;
    c.far_misses += __builtin_popcount(_mm256_movemask_ps(_mm256_andnot_ps(_mm256_or_ps(close, near), ok)));
  }
};

__m256i stripLanes(int remaining) {
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(remaining), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}
#endif

RowCounts countRow(const float* row, int u0, int u1, float road_max, float d, float tol, float near_lo) {
  RowCounts c;
#ifdef __AVX2__
  const LaneTest test(d, tol, near_lo);
  for (int u = u0; u < u1; u += 8) test.add(c, _mm256_maskload_ps(row + u, stripLanes(u1 - u)), road_max);
#else
  // Without a branch per pixel (the tests mispredict on a ragged disparity), so that
  // GCC also vectorises it for SSE4 and NEON: the same counts as the AVX2 lanes.
  int valid = 0, matches = 0, far_misses = 0;
  for (int u = u0; u < u1; ++u) {
    const float x = row[u];
    const bool ok = (x > 0.0f) & (x < kInf) & (x > road_max);  // NaN fails
    const bool close = std::abs(x - d) <= tol;
    const bool near = (x < d) & (x >= near_lo);
    valid += ok;
    matches += ok & close;
    far_misses += ok & !(close | near);
  }
  c.valid = valid;
  c.matches = matches;
  c.misses = valid - matches;
  c.far_misses = far_misses;
#endif
  return c;
}

}  // namespace

int segmentTopRow(const cv::Mat& disparity, const GroundModel& g, float ground_tolerance_m,
                  int u0, int u1, int foot_row, int limit_row, float d, const TopSearch& t) {
  // Two scores in one pass: the plain one (a near miss is -1) and the bridged one
  // (a near miss is 0), and per row its matches and valid pixels.
  int best_row = foot_row;
  if (foot_row < limit_row) return best_row;
  int sum = 0, best = 0;
  const bool bridge = t.near_miss_px > 0.0f && t.max_extension_rows > 0;
  struct Row { int bridged, matches, valid; };
  thread_local std::vector<Row> rows;
  if (bridge) rows.resize(static_cast<size_t>(foot_row - limit_row + 1));
  int bsum = 0;
  const float h = g.height_m;
  const float near_lo = d - t.tolerance_px - t.near_miss_px;
  // Road at a row: height h*(x - dg)/x <= tol  <=>  x*(h - tol) <= h*dg.
  auto roadMax = [&](int v) { return h * g.groundDisparity(static_cast<float>(v)) / (h - ground_tolerance_m); };
  auto account = [&](int v, const RowCounts& c) {
    sum += c.matches - c.misses;
    bsum += c.matches - c.far_misses;
    if (sum > best) best = sum, best_row = v;
    if (bridge) rows[static_cast<size_t>(foot_row - v)] = {bsum, c.matches, c.valid};
  };
#ifdef __AVX2__
  if (u1 - u0 <= 8 && u1 > u0) {
    // A strip of one register (the default widths): its lane mask and the
    // constants stay in registers over the rows.
    const __m256i in_strip = stripLanes(u1 - u0);
    const LaneTest test(d, t.tolerance_px, near_lo);
    for (int v = foot_row; v >= limit_row; --v) {
      RowCounts c;
      test.add(c, _mm256_maskload_ps(disparity.ptr<float>(v) + u0, in_strip), roadMax(v));
      account(v, c);
    }
  } else
#endif
    for (int v = foot_row; v >= limit_row; --v)
      account(v, countRow(disparity.ptr<float>(v), u0, u1, roadMax(v), d, t.tolerance_px, near_lo));
  if (!bridge) return best_row;
  // The bridged argmax at most max_extension_rows above the plain top ...
  const int from = std::max(limit_row, best_row - t.max_extension_rows);
  int bbest = rows[foot_row - best_row].bridged, top = best_row;
  for (int v = best_row - 1; v >= from; --v) {
    const int s = rows[foot_row - v].bridged;
    if (s > bbest) bbest = s, top = v;
  }
  // ... is taken when the object resumes above the band: at least
  // min_resume_rows rows between it and the plain top are mostly at its
  // disparity (a head over a torso read toward the background; a surface
  // behind at the near-miss disparity has only stray matches above it).
  int resumed = 0;
  for (int v = top; v < best_row; ++v) {
    const Row& r = rows[foot_row - v];
    if (2 * r.matches > r.valid) ++resumed;
  }
  return resumed >= std::max(1, t.min_resume_rows) ? top : best_row;
}

float medianObstacleDisparity(const cv::Mat& disparity, const GroundModel& g, const FreeSpaceParams& fs,
                              int u0, int u1, int v0, int v1, float lo, float hi, std::vector<float>& samples) {
  samples.clear();
  for (int v = v0; v <= v1; ++v) {
    const float* row = disparity.ptr<float>(v);
    for (int u = u0; u < u1; ++u) {
      const float d = row[u];
      if (!(d >= lo && d < hi)) continue;
      const float hg = heightAboveGround(g, static_cast<float>(v), d);
      if (hg > fs.ground_tolerance_m && hg < fs.max_height_above_ground_m) samples.push_back(d);
    }
  }
  if (samples.empty()) return 0.0f;
  auto mid = samples.begin() + samples.size() / 2;
  std::nth_element(samples.begin(), mid, samples.end());
  return *mid;
}

bool stixelAtDisparity(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& g,
                       const StixelExtractionParams& p, int u0, int u1, float d, int max_bottom_row, Stixel& st) {
  const float a = g.vd_slope, b = g.vd_intercept, h = g.height_m;
  const double fb = cam.fx * cam.baseline_m;
  const int foot = std::clamp(static_cast<int>(std::lround((d - b) / a)), 0, disparity.rows - 1);
  const int bottom = std::min(foot, max_bottom_row);
  // Row where a point of disparity d has height max_stixel_height_m over the road.
  const float limit_row = (d * (1.0f - p.max_stixel_height_m / h) - b) / a;
  const int limit = std::clamp(static_cast<int>(std::ceil(limit_row)), 0, std::max(bottom, 0));
  const double z = fb / d;
  const float tol_px = disparityTolerance(d, cam, p.object_depth_tolerance_m);
  TopSearch ts;
  ts.tolerance_px = tol_px;
  ts.near_miss_px = p.top_near_miss_px;
  ts.max_extension_rows = static_cast<int>(std::floor(p.top_max_extension_m * cam.fy / z));
  ts.min_resume_rows = static_cast<int>(std::ceil(p.top_min_resume_m * cam.fy / z));
  const int top = segmentTopRow(disparity, g, p.free_space.ground_tolerance_m, u0, u1, bottom, limit, d, ts);
  if ((bottom - top + 1) * z / cam.fy < p.free_space.min_obstacle_height_m) return false;
  st = Stixel{};
  st.u = u0;
  st.width = u1 - u0;
  st.top_row = top;
  st.bottom_row = bottom;
  st.disparity = d;
  st.depth_m = static_cast<float>(z);
  const Point3 base = cam.toPoint(0.5 * (u0 + u1), foot, d);
  st.base_x_m = static_cast<float>(base.x);
  st.base_y_m = static_cast<float>(base.y);
  st.base_z_m = static_cast<float>(base.z);
  return true;
}

std::vector<Stixel> extractStixels(const cv::Mat& disparity, const StereoCamera& cam,
                                   const GroundModel& g, const std::vector<int>& boundary,
                                   const StixelExtractionParams& p) {
  return extractStixels(disparity, obstacleDisparityMap(disparity, g, p.free_space), cam, g, boundary, p);
}

std::vector<Stixel> extractStixels(const cv::Mat& disparity, const cv::Mat& obstacle_map, const StereoCamera& cam,
                                   const GroundModel& g, const std::vector<int>& boundary,
                                   const StixelExtractionParams& p) {
  const FreeSpaceParams& fs = p.free_space;
  const int cw = std::max(1, fs.column_width_px);
  const int rows = disparity.rows;
  const float a = g.vd_slope, b = g.vd_intercept, h = g.height_m;
  // Row where a point of disparity d has height `height_m` over the road:
  // h*(d - dg(v))/d = height_m  <=>  dg(v) = d*(1 - height_m/h).
  auto rowAtHeight = [&](float d, float height_m) { return (d * (1.0f - height_m / h) - b) / a; };

  std::vector<float> samples;
  std::vector<Stixel> out;
  for (size_t s = 0; s < boundary.size(); ++s) {
    const int k = boundary[s];
    if (k < 0) continue;
    const int u0 = static_cast<int>(s) * cw;
    const int u1 = std::min(disparity.cols, u0 + cw);
    const int hw = obstacleHalfWindow(k);
    const float dlo = static_cast<float>(std::max(k - hw, 0)), dhi = static_cast<float>(k + hw + 1);

    // Robust disparity: median of the strip's obstacle pixels in the boundary window.
    const int v_from = std::clamp(static_cast<int>(std::floor(rowAtHeight(dhi, fs.max_height_above_ground_m))), 0, rows - 1);
    const int v_to = std::clamp(static_cast<int>(std::ceil(rowAtHeight(dlo, 0.0f))), 0, rows - 1);
    const float d = medianInRange(obstacle_map, u0, u1, v_from, v_to, dlo, dhi, samples);
    if (d <= 0.0f) continue;
    Stixel st;
    if (stixelAtDisparity(disparity, cam, g, p, u0, u1, d, rows - 1, st)) out.push_back(st);
  }
  return out;
}

}  // namespace nerv::stixel

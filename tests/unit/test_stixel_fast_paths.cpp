// The stixel stage's fast paths against plain loops written from their
// definitions, on random disparity maps with invalid, NaN and infinite pixels:
// the vectorised top search (segmentTopRow) for strip widths that fill one, two
// and three SIMD registers or part of one, the occupancy votes (buildOccupancy),
// the free space that scores only a strip's occupied bins (solveFreeSpace), and
// the per-frame obstacle map with the median over it (obstacle_map.hpp). Each
// must give exactly the plain loop's result.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "free_space.hpp"
#include "ground_geometry.hpp"
#include "obstacle_map.hpp"
#include "stixel_extraction.hpp"

namespace nerv::stixel {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

GroundModel flatRoad() {
  GroundModel g;
  g.valid = true;
  g.vd_slope = 0.327f;
  g.vd_intercept = -0.327f * 150.0f;
  g.horizon_row = 150.0f;
  g.height_m = 1.65f;
  return g;
}

StereoCamera camera(int cols, int rows) {
  StereoCamera c;
  c.width = cols;
  c.height = rows;
  c.fx = c.fy = 722.0;
  c.cx = cols / 2.0;
  c.cy = 150.0;
  c.baseline_m = 0.54;
  return c;
}

// Road below the horizon, with blocks of obstacles and scattered bad pixels.
cv::Mat randomDisparity(int cols, int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const GroundModel g = flatRoad();
  cv::Mat d(rows, cols, CV_32F);
  for (int v = 0; v < rows; ++v)
    for (int u = 0; u < cols; ++u) d.at<float>(v, u) = std::max(0.0f, g.groundDisparity(v)) + 0.5f * unit(rng);
  for (int k = 0; k < 12; ++k) {  // obstacles: a disparity over a block of rows and columns
    const int u0 = static_cast<int>(unit(rng) * (cols - 20)), w = 3 + static_cast<int>(unit(rng) * 17);
    const int foot = 160 + static_cast<int>(unit(rng) * (rows - 161));
    const float disp = std::max(1.0f, g.groundDisparity(foot));
    const int top = std::max(0, foot - static_cast<int>(unit(rng) * 120));
    for (int v = top; v <= foot; ++v)
      for (int u = u0; u < u0 + w; ++u) d.at<float>(v, u) = disp + (unit(rng) - 0.5f) * 2.0f;
  }
  for (int v = 0; v < rows; ++v)
    for (int u = 0; u < cols; ++u) {
      const float r = unit(rng);
      float& x = d.at<float>(v, u);
      if (r < 0.05f) x = 0.0f;
      else if (r < 0.06f) x = kNan;
      else if (r < 0.065f) x = kInf;
      else if (r < 0.07f) x = -1.0f;
    }
  return d;
}

// segmentTopRow as its header defines it, one pixel at a time.
int plainTopRow(const cv::Mat& disp, const GroundModel& g, float tol_m, int u0, int u1, int foot, int limit,
                float d, const TopSearch& t) {
  int best_row = foot, sum = 0, best = 0, bsum = 0;
  struct Row { int bridged, matches, valid; };
  std::vector<Row> rows;
  const float h = g.height_m, near_lo = d - t.tolerance_px - t.near_miss_px;
  for (int v = foot; v >= limit; --v) {
    const float road_max = h * g.groundDisparity(static_cast<float>(v)) / (h - tol_m);
    int matches = 0, valid = 0;
    for (int u = u0; u < u1; ++u) {
      const float x = disp.at<float>(v, u);
      if (!(x > 0.0f) || !std::isfinite(x) || x <= road_max) continue;
      ++valid;
      if (std::abs(x - d) <= t.tolerance_px) {
        ++sum, ++bsum, ++matches;
      } else {
        --sum;
        if (!(x < d && x >= near_lo)) --bsum;
      }
    }
    if (sum > best) best = sum, best_row = v;
    rows.push_back({bsum, matches, valid});
  }
  if (!(t.near_miss_px > 0.0f && t.max_extension_rows > 0)) return best_row;
  const int from = std::max(limit, best_row - t.max_extension_rows);
  int bbest = rows[foot - best_row].bridged, top = best_row;
  for (int v = best_row - 1; v >= from; --v)
    if (rows[foot - v].bridged > bbest) bbest = rows[foot - v].bridged, top = v;
  int resumed = 0;
  for (int v = top; v < best_row; ++v)
    if (2 * rows[foot - v].matches > rows[foot - v].valid) ++resumed;
  return resumed >= std::max(1, t.min_resume_rows) ? top : best_row;
}

TEST(stixelFastPaths, TopSearchCountsAsThePlainLoopForEveryStripWidth) {
  const cv::Mat disp = randomDisparity(203, 240, 7);
  const GroundModel g = flatRoad();
  std::mt19937 rng(11);
  int cases = 0, raised = 0;
  for (int width : {1, 3, 5, 7, 8, 9, 13, 16, 17, 24}) {
    for (int k = 0; k < 40; ++k, ++cases) {
      const int u0 = static_cast<int>(rng() % (203 - width + 1));
      const int foot = 170 + static_cast<int>(rng() % 70), limit = static_cast<int>(rng() % 100);
      // Mostly the disparity of a pixel just above the foot (an obstacle there has a top to find).
      const float at = disp.at<float>(foot - 5, u0);
      const float d = k % 4 != 0 && at > 1.0f && std::isfinite(at) ? at : 2.0f + static_cast<float>(rng() % 300) / 10.0f;
      TopSearch t;
      t.tolerance_px = 0.5f + static_cast<float>(rng() % 10) / 10.0f;
      t.near_miss_px = k % 3 == 0 ? 0.0f : 1.5f;
      t.max_extension_rows = static_cast<int>(rng() % 30);
      t.min_resume_rows = 1 + static_cast<int>(rng() % 3);
      const int fast = segmentTopRow(disp, g, 0.15f, u0, u0 + width, foot, limit, d, t);
      const int plain = plainTopRow(disp, g, 0.15f, u0, u0 + width, foot, limit, d, t);
      ASSERT_EQ(fast, plain) << "width " << width << " u0 " << u0 << " foot " << foot << " d " << d;
      raised += fast < foot;
    }
  }
  EXPECT_GT(raised, cases / 4);  // the cases do find tops, not only the foot row
}

TEST(stixelFastPaths, TopSearchAtTheImagesLastColumnsAndRow) {
  // The strip's last SIMD register reaches past the row's end: masked lanes are not read.
  const cv::Mat disp = randomDisparity(37, 240, 3);
  const GroundModel g = flatRoad();
  TopSearch t;
  t.near_miss_px = 1.5f;
  t.max_extension_rows = 10;
  for (int width = 1; width <= 12; ++width)
    EXPECT_EQ(segmentTopRow(disp, g, 0.15f, 37 - width, 37, 239, 0, 20.0f, t),
              plainTopRow(disp, g, 0.15f, 37 - width, 37, 239, 0, 20.0f, t));
}

TEST(stixelFastPaths, OccupancyVotesAsThePlainLoop) {
  for (int cols : {203, 205, 64, 13}) {  // with and without a tail of fewer than eight columns
    const cv::Mat disp = randomDisparity(cols, 240, 5 + cols);
    const GroundModel g = flatRoad();
    FreeSpaceParams p;
    const OccupancyGrid grid = buildOccupancy(disp, camera(cols, 240), g, p);
    // The plain votes: each obstacle pixel (inside the row's window) counts in its strip and bin.
    std::vector<float> lo, hi;
    obstacleDisparityWindow(g, 240, p.ground_tolerance_m, p.max_height_above_ground_m, lo, hi);
    const float d_min = static_cast<float>(camera(cols, 240).disparityFromDepth(p.max_distance_m));
    std::vector<int> count(grid.filled_m.size(), 0), top(grid.filled_m.size(), 240);
    int voted = 0;
    for (int v = 0; v < 240; ++v)
      for (int u = 0; u < cols; ++u) {
        const float d = disp.at<float>(v, u);
        if (!(d > std::max(lo[v], d_min) && d < std::min(hi[v], p.max_disparity_px))) continue;
        const size_t i = grid.index(u / p.column_width_px, static_cast<int>(d));
        ++count[i], ++voted;
        top[i] = std::min(top[i], v);
      }
    ASSERT_GT(voted, 100);
    const double k = 722.0 * 0.54 / 722.0;
    for (int s = 0; s < grid.strips; ++s)
      for (int b = grid.min_bin; b < grid.end_bin; ++b) {
        const size_t i = grid.index(s, b);
        const int w = std::min(p.column_width_px, cols - s * p.column_width_px);
        const float d = b + 0.5f;
        EXPECT_EQ(grid.filled_m[i], count[i] ? static_cast<float>(count[i] * k / (w * d)) : 0.0f) << s << " " << b;
        if (count[i]) {
          EXPECT_EQ(grid.reach_m[i], g.height_m * (d - g.groundDisparity(static_cast<float>(top[i]))) / d);
        }
      }
  }
}

TEST(stixelFastPaths, FreeSpaceScoresOnlyOccupiedBinsWithTheSameResult) {
  const cv::Mat disp = randomDisparity(203, 240, 21);
  FreeSpaceParams p;
  const OccupancyGrid grid = buildOccupancy(disp, camera(203, 240), flatRoad(), p);
  // Outside a strip's occupied bins every score is 0, so skipping them changes nothing.
  int occupied = 0;
  for (int s = 0; s < grid.strips; ++s)
    for (int k = grid.min_bin; k < grid.end_bin; ++k) {
      bool any = false;
      const int hw = obstacleHalfWindow(k);
      for (int j = std::max(grid.min_bin, k - hw); j < std::min(grid.end_bin, k + hw + 1); ++j)
        any = any || grid.filled_m[grid.index(s, j)] > 0;
      if (!any) {
        EXPECT_EQ(obstacleScore(grid, s, k), 0.0f);
      }
      occupied += any;
    }
  EXPECT_GT(occupied, 0);
  const std::vector<int> boundary = solveFreeSpace(grid, p);
  int obstacles = 0;
  for (int b : boundary) obstacles += b >= 0;
  EXPECT_GT(obstacles, 0);
}

TEST(stixelFastPaths, ObstacleMapHoldsTheObstaclePixelsAndItsMedianIsTheDirectOne) {
  const cv::Mat disp = randomDisparity(203, 240, 9);
  const GroundModel g = flatRoad();
  FreeSpaceParams fs;
  const cv::Mat map = obstacleDisparityMap(disp, g, fs);
  ASSERT_EQ(map.size(), disp.size());
  ASSERT_EQ(map.type(), CV_32F);
  int obstacles = 0;
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 203; ++u) {
      const float d = disp.at<float>(v, u), hg = heightAboveGround(g, static_cast<float>(v), d);
      const bool obstacle = hg > fs.ground_tolerance_m && hg < fs.max_height_above_ground_m;
      if (obstacle) {
        EXPECT_EQ(map.at<float>(v, u), d);
      } else {
        EXPECT_TRUE(std::isnan(map.at<float>(v, u))) << v << " " << u;
      }
      obstacles += obstacle;
    }
  EXPECT_GT(obstacles, 1000);
  std::vector<float> a, b;
  std::mt19937 rng(4);
  // Strip widths 1-24: one register, several, and a last register only partly
  // in the strip; the strip may end at the image's last column.
  for (int k = 0; k < 400; ++k) {
    const int width = 1 + k % 24;
    const int u0 = k % 7 == 0 ? disp.cols - width : static_cast<int>(rng() % static_cast<unsigned>(disp.cols - width));
    const int v0 = static_cast<int>(rng() % 200);
    const float lo = static_cast<float>(rng() % 40), hi = lo + 1.0f + static_cast<float>(rng() % 10);
    EXPECT_EQ(medianInRange(map, u0, u0 + width, v0, v0 + 39, lo, hi, a),
              medianObstacleDisparity(disp, g, fs, u0, u0 + width, v0, v0 + 39, lo, hi, b))
        << "width " << width << " u0 " << u0;
  }
}

}  // namespace
}  // namespace nerv::stixel

// Foreground fattening correction: constructed rows against the rule, random
// rows against a plain reference implementation of it, and a rendered post
// (known edges) through nerv_sgm with and without it.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "boundary_snap.hpp"
#include "stereo_matcher.hpp"

using namespace nerv::stereo;

namespace {

// One row: gray and disparity as given.
struct Row {
  cv::Mat gray, disp, conf;
  Row(std::vector<int> g, std::vector<float> d)
      : gray(1, int(g.size()), CV_8U), disp(1, int(d.size()), CV_32F), conf(1, int(d.size()), CV_32F, 1.0f) {
    for (size_t i = 0; i < g.size(); ++i) gray.at<uchar>(0, int(i)) = uchar(g[i]), disp.at<float>(0, int(i)) = d[i];
  }
  float d(int x) const { return disp.at<float>(0, x); }
};

BoundarySnapParams band(int b) {
  BoundarySnapParams p;
  p.band_px = b;
  return p;
}

// The rule of boundary_snap.hpp written out plainly, one pixel and one
// direction at a time, without the candidate pass, the skipping and the
// threads of the real one.
namespace reference {

float nextValid(const cv::Mat& d, int x, int step, int search) {
  for (int k = 0; k < search; ++k, x += step) {
    if (x < 0 || x >= d.cols) return 0.0f;
    if (d.at<float>(0, x) > 0.0f) return d.at<float>(0, x);
  }
  return 0.0f;
}

// Where the background begins when valid pixel x ends a foreground region towards step, or -1.
int backgroundStart(const cv::Mat& row, int x, int step, const BoundarySnapParams& p) {
  auto inside = [&](int i) { return i >= 0 && i < row.cols; };
  auto d = [&](int i) { return row.at<float>(0, i); };
  const int n = x + step;
  if (!inside(n)) return -1;
  if (!(d(n) > 0.0f)) {  // across invalid pixels
    const float beyond = nextValid(row, n, step, p.hole_search_px);
    return beyond == 0.0f || d(x) - beyond > p.jump_px ? n : -1;
  }
  if (d(x) - d(n) > p.jump_px) return n;  // a step
  // A falling ramp of up to band pixels between two flat sides, which has
  // fallen by more than jump at band + 1 pixels too.
  const int far = x + (p.band_px + 1) * step;
  if (!inside(far) || !(d(x) - d(far) > p.jump_px)) return -1;
  for (int m = 2; m <= p.band_px + 1; ++m) {
    const int k = x + m * step;
    if (!inside(k) || !(d(k) > 0.0f) || d(k) > d(k - step) + 0.1f) return -1;
    const float fall = d(x) - d(k);
    if (fall <= p.jump_px) continue;
    const float slope = fall / static_cast<float>(m);
    const int before = x - step, after = k + step;
    const bool flat_before = inside(before) && d(before) > 0.0f && std::abs(d(x) - d(before)) < 0.5f * slope;
    const bool flat_after = inside(after) && d(after) > 0.0f && std::abs(d(k) - d(after)) < 0.5f * slope;
    return flat_before && flat_after ? k : -1;
  }
  return -1;
}

int snapRow(const cv::Mat& gray, cv::Mat& row, cv::Mat& conf, const BoundarySnapParams& p) {
  const int cols = row.cols, reach = p.band_px + 1;
  auto d = [&](int i) { return row.at<float>(0, i); };
  std::vector<bool> cut(static_cast<size_t>(cols), false);
  for (int x = 0; x < cols; ++x) {
    if (!(d(x) > 0.0f)) continue;
    for (const int step : {+1, -1}) {
      const int bg = backgroundStart(row, x, step, p);
      if (bg < 0) continue;
      // strongest intensity step between e and e + step, from band pixels
      // inside x (while the object goes on) to the pixel before the background
      // a run shorter than 3 * reach pixels (from the pixel before the background to
      // the last one inwards within jump of d(x)) is searched on this side's half only
      int far_end = -1;
      for (int k = 1; k <= 3 * reach && far_end < 0; ++k) {
        const int i = x - k * step;
        if (i < 0 || i >= cols || !(d(i) > d(x) - p.jump_px)) far_end = i + step;
      }
      int best = x, best_step = 0;
      for (int e = bg - step; e != x - reach * step; e -= step) {
        if (e < 0 || e >= cols || e + step < 0 || e + step >= cols) break;
        if ((e - x) * step <= 0 && !(d(e) > d(x) - p.jump_px)) break;
        // the edge between e and e + step lies beyond the middle of [bg - step, far_end]
        if (far_end >= 0 && (e + 0.5 * step - 0.5 * (bg - step + far_end)) * step < 0) break;
        const int st = std::abs(int(gray.at<uchar>(0, e + step)) - int(gray.at<uchar>(0, e)));
        if (st > best_step) best_step = st, best = e;
      }
      if (best_step >= p.min_step)
        for (int k = best + step; k != bg; k += step) cut[static_cast<size_t>(k)] = true;
    }
  }
  int removed = 0;
  for (int x = 0; x < cols; ++x)
    if (cut[static_cast<size_t>(x)]) {
      row.at<float>(0, x) = 0.0f;
      if (!conf.empty()) conf.at<float>(0, x) = 0.0f;
      ++removed;
    }
  return removed;
}

int snap(const cv::Mat& gray, cv::Mat& disparity, cv::Mat& confidence, const BoundarySnapParams& p) {
  int removed = 0;
  for (int v = 0; v < disparity.rows; ++v) {
    cv::Mat row = disparity.row(v), conf = confidence.empty() ? cv::Mat() : confidence.row(v);
    removed += snapRow(gray.row(v), row, conf, p);
  }
  return removed;
}

}  // namespace reference

}  // namespace

TEST(stereoBoundarySnap, CutsFattenedPixelsBackToTheIntensityEdge) {
  // Object at columns 5..7 (gray 40) fattened to 3..9; background 10 px farther.
  Row r({120, 121, 119, 122, 120, 40, 41, 40, 121, 120, 122, 119},
        {10, 10, 0, 20, 20, 20, 20, 20, 20, 20, 10, 10});
  EXPECT_EQ(snapDisparityBoundaries(r.gray, r.disp, r.conf, band(4)), 4);
  for (int x : {3, 4, 8, 9}) EXPECT_EQ(r.d(x), 0.0f) << x;
  for (int x : {5, 6, 7}) EXPECT_EQ(r.d(x), 20.0f) << x;
  EXPECT_EQ(r.conf.at<float>(0, 3), 0.0f);
  EXPECT_EQ(r.d(0), 10.0f);  // background untouched
}

TEST(stereoBoundarySnap, CutsASmoothedStepDownToTheEdge) {
  // Object at 6..9 (gray 40) whose right boundary the matcher smoothed into a
  // ramp 20 -> 10 over columns 10..12; background flat from 13.
  Row r({120, 121, 119, 122, 120, 121, 40, 41, 40, 42, 120, 121, 119, 122, 120, 121},
        {10, 10, 10, 10, 10, 10, 20, 20, 20, 20, 17, 14, 12, 10, 10, 10});
  snapDisparityBoundaries(r.gray, r.disp, r.conf, band(4));
  for (int x : {6, 7, 8, 9}) EXPECT_EQ(r.d(x), 20.0f) << x;
  for (int x : {10, 11, 12}) EXPECT_EQ(r.d(x), 0.0f) << x;
  for (int x : {13, 14, 15}) EXPECT_EQ(r.d(x), 10.0f) << x;
}

TEST(stereoBoundarySnap, KeepsAThinPostWhoseFarSideIsTheStrongerStep) {
  // A post at 20..23 (gray 120) between a bright background on its left (140: a step of
  // 20) and a dimmer one on its right (128: a step of 8), fattened to 16..19 on the left and
  // smoothed into a ramp over 24..27 on the right (urban seed 11 frame 3 row 208: a post of
  // 4 px at 22 m). Both of its sides lie within the right boundary's band, and the left one
  // is the stronger step: cut there, the right boundary took the post with it.
  std::vector<int> g(34, 140);
  std::vector<float> d(34, 10.0f);
  for (int x = 20; x < 34; ++x) g[x] = x < 24 ? 120 : 128;
  for (int x = 16; x < 24; ++x) d[x] = 18.0f;
  const float ramp[] = {17.9f, 17.8f, 17.7f, 17.6f, 14.8f};
  for (int i = 0; i < 5; ++i) d[24 + i] = ramp[i];
  for (int x = 29; x < 34; ++x) d[x] = 14.6f;
  Row r(g, d);
  snapDisparityBoundaries(r.gray, r.disp, r.conf, band(4));
  for (int x = 16; x < 20; ++x) EXPECT_EQ(r.d(x), 0.0f) << x;   // fattened on the left
  for (int x = 20; x < 24; ++x) EXPECT_EQ(r.d(x), 18.0f) << x;  // the post
  for (int x = 24; x < 28; ++x) EXPECT_EQ(r.d(x), 0.0f) << x;   // the ramp on its right
  EXPECT_EQ(r.d(15), 10.0f);
  EXPECT_EQ(r.d(28), 14.8f);
}

TEST(stereoBoundarySnap, LeavesASlantedSurfaceAlone) {
  // Constant slope 0.5 px per column (a wall at a grazing angle) with texture.
  std::vector<int> g;
  std::vector<float> d;
  for (int x = 0; x < 24; ++x) g.push_back(x % 2 ? 60 : 140), d.push_back(20.0f - 0.5f * x);
  Row r(g, d);
  EXPECT_EQ(snapDisparityBoundaries(r.gray, r.disp, r.conf, band(4)), 0);
}

TEST(stereoBoundarySnap, LeavesBoundariesWithoutAnIntensityEdge) {
  Row r({120, 121, 119, 122, 120, 121, 119, 120, 121, 120, 122, 119},
        {10, 10, 10, 20, 20, 20, 20, 20, 20, 20, 10, 10});
  EXPECT_EQ(snapDisparityBoundaries(r.gray, r.disp, r.conf, band(4)), 0);
}

TEST(stereoBoundarySnap, AHoleInsideAnObjectIsNotABoundary) {
  // Invalid run inside the object, object continues beyond it at the same depth.
  Row r({120, 40, 60, 40, 60, 40, 60, 40, 60, 40, 60, 120},
        {10, 20, 20, 20, 0, 0, 0, 20, 20, 20, 20, 10});
  r.disp.at<float>(0, 0) = 20;  // object reaches the image edge on the left
  const int removed = snapDisparityBoundaries(r.gray, r.disp, r.conf, band(2));
  for (int x : {1, 2, 3, 7, 8}) EXPECT_EQ(r.d(x), 20.0f) << x;
  EXPECT_LE(removed, 1);  // only the right boundary at column 10 may move
}

TEST(stereoBoundarySnap, ZeroBandAndEmptyConfidenceAreAccepted) {
  Row r({120, 40, 40, 120}, {10, 20, 20, 10});
  cv::Mat no_conf;
  EXPECT_EQ(snapDisparityBoundaries(r.gray, r.disp, no_conf, band(0)), 0);
}

// Random rows of flat and slanted pieces, steps, smoothed ramps, single-pixel
// rises and holes, on a 1/16 px grid so that falls of exactly jump occur,
// against the plain reference, for several bands, thresholds and widths
// (also narrower than two bands).
TEST(stereoBoundarySnap, MatchesThePlainReferenceOnRandomRows) {
  std::mt19937 rng(5);
  int total_removed = 0;
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int trial = 0; trial < 300; ++trial) {
    BoundarySnapParams p;
    p.band_px = uniform(0, 6);
    p.jump_px = trial % 3 ? 1.5f : 1.0f;
    p.min_step = std::vector<int>{8, 0, 30}[static_cast<size_t>(trial % 3)];
    p.hole_search_px = std::vector<int>{16, 3, 1, 0, 1000}[static_cast<size_t>(trial / 3 % 5)];
    const int rows = uniform(1, 40), cols = trial < 40 ? uniform(1, 14) : uniform(15, 300);
    cv::Mat gray(rows, cols, CV_8U), disp(rows, cols, CV_32F), conf(rows, cols, CV_32F);
    for (int v = 0; v < rows; ++v) {
      float level = uniform(1, 60) / 2.0f, slope = 0.0f;
      int gray_level = uniform(0, 255);
      for (int x = 0; x < cols; ++x) {
        const int event = uniform(0, 99);
        if (event < 8) level = uniform(1, 60) / 2.0f;                          // a step
        else if (event < 12) level = std::max(0.0625f, level - uniform(1, 40) / 16.0f);  // a ramp pixel
        else if (event < 15) slope = uniform(-8, 8) / 16.0f;                 // a slanted piece
        else if (event < 18) slope = 0.0f;
        level = std::max(0.0625f, level + slope);
        float value = level;
        if (event >= 18 && event < 24) value = 0.0f;                       // a hole pixel
        else if (event >= 24 && event < 30) value = level + uniform(-3, 3) / 16.0f;  // noise, rises
        if (uniform(0, 99) < 15) gray_level = uniform(0, 255);              // an intensity edge
        gray.at<uchar>(v, x) = static_cast<uchar>(std::clamp(gray_level + uniform(-3, 3), 0, 255));
        disp.at<float>(v, x) = value;
        conf.at<float>(v, x) = value > 0.0f ? uniform(1, 100) / 100.0f : 0.0f;
      }
    }
    cv::Mat fast_d = disp.clone(), fast_c = conf.clone(), ref_d = disp.clone(), ref_c = conf.clone();
    const int fast_n = snapDisparityBoundaries(gray, fast_d, fast_c, p);
    const int ref_n = reference::snap(gray, ref_d, ref_c, p);
    ASSERT_EQ(fast_n, ref_n) << "trial " << trial;
    ASSERT_EQ(cv::norm(fast_d, ref_d, cv::NORM_INF), 0.0) << "trial " << trial;
    ASSERT_EQ(cv::norm(fast_c, ref_c, cv::NORM_INF), 0.0) << "trial " << trial;
    cv::Mat fast_d2 = disp.clone(), no_conf;  // without confidence
    ASSERT_EQ(snapDisparityBoundaries(gray, fast_d2, no_conf, p), ref_n) << "trial " << trial;
    ASSERT_EQ(cv::norm(fast_d2, ref_d, cv::NORM_INF), 0.0) << "trial " << trial;
    total_removed += ref_n;
  }
  EXPECT_GT(total_removed, 5000) << "the random rows hardly exercise the rule";
}

// A dark textured post 10 px wide at disparity 24 in front of a textured wall
// at disparity 8: nerv_sgm's census 9x7 widens it; the correction restores
// its edges.
TEST(stereoBoundarySnap, RenderedPostKeepsItsWidthThroughNervSgm) {
  const int rows = 120, cols = 320, x0 = 150, x1 = 160, d_post = 24, d_wall = 8;
  cv::Mat wall(rows, cols + 64, CV_8U), post(rows, cols + 64, CV_8U);
  cv::RNG rng(7);
  rng.fill(wall, cv::RNG::UNIFORM, 90, 230);
  rng.fill(post, cv::RNG::UNIFORM, 10, 70);
  cv::GaussianBlur(wall, wall, cv::Size(0, 0), 1.5);
  cv::GaussianBlur(post, post, cv::Size(0, 0), 1.5);
  cv::Mat left(rows, cols, CV_8U), right(rows, cols, CV_8U);
  for (int v = 0; v < rows; ++v)
    for (int x = 0; x < cols; ++x) {
      left.at<uchar>(v, x) = x >= x0 && x < x1 ? post.at<uchar>(v, x) : wall.at<uchar>(v, x);
      const int xl = x + d_post;  // right pixel x sees the post where x + d_post is on it
      right.at<uchar>(v, x) = xl >= x0 && xl < x1 ? post.at<uchar>(v, xl) : wall.at<uchar>(v, x + d_wall);
    }

  auto postWidths = [&](int snap) {
    Params p;
    p.boundary_snap_px = snap;
    // the 9x7 window everywhere: this is the snap's test, and a post filling the
    // whole height is no road scene (nerv_sgm's road band matches a 10 px post
    // less well: docs/stereo.md "Road accuracy")
    p.road_census_from = 1.0;
    p.num_disparities = 64;
    cv::Mat d;
    StereoMatcher::create(p)->compute(left, right, d);
    std::vector<int> widths;
    for (int v = 10; v < rows - 10; ++v) {
      int n = 0;
      for (int x = x0 - 12; x < x1 + 12; ++x) n += d.at<float>(v, x) > 0.5f * (d_post + d_wall) ? 1 : 0;
      widths.push_back(n);
    }
    std::sort(widths.begin(), widths.end());
    return widths;
  };
  const std::vector<int> raw = postWidths(0), snapped = postWidths(-1);
  const int true_w = x1 - x0;
  EXPECT_GE(raw[raw.size() / 2], true_w + 2) << "the fattening this corrects is no longer there";
  EXPECT_NEAR(snapped[snapped.size() / 2], true_w, 1);
  int close = 0;
  for (int w : snapped) close += std::abs(w - true_w) <= 1 ? 1 : 0;
  EXPECT_GE(close, int(0.85 * snapped.size())) << "raw median " << raw[raw.size() / 2];
}

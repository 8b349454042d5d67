#include "gap_columns.hpp"

#include <algorithm>
#include <cmath>

#include "ground_geometry.hpp"
#include "height_steps.hpp"
#include "nearest_per_strip.hpp"
#include "strip_run.hpp"

namespace nerv::stixel {
namespace {

// Median and lower quartile of the disparities of column u over rows
// [v0, v1] (valid pixels above the road); zeros when fewer than a third of
// the rows hold one.
struct ColumnStats {
  float median = 0.0f, q25 = 0.0f;
};

ColumnStats columnStats(const cv::Mat& disparity, const GroundModel& ground, float ground_tolerance_m, int u, int v0,
                        int v1, std::vector<float>& scratch) {
  scratch.clear();
  for (int v = v0; v <= v1; ++v) {
    const float x = disparity.ptr<float>(v)[u];
    if (!(x > 0 && std::isfinite(x))) continue;
    if (heightAboveGround(ground, static_cast<float>(v), x) <= ground_tolerance_m) continue;
    scratch.push_back(x);
  }
  if (3 * static_cast<int>(scratch.size()) < v1 - v0 + 1) return {};
  const auto mid = scratch.begin() + scratch.size() / 2, quarter = scratch.begin() + scratch.size() / 4;
  std::nth_element(scratch.begin(), mid, scratch.end());
  std::nth_element(scratch.begin(), quarter, mid);
  return {*mid, *quarter};
}

// The statistics of the group's columns over one row range, each computed
// once: the ends tried one after another mostly share their rows.
class ColumnCache {
 public:
  ColumnCache(const cv::Mat& disparity, const GroundModel& ground, float ground_tolerance_m, int u0, int u1)
      : disparity_(disparity), ground_(ground), tol_(ground_tolerance_m), u0_(u0), stats_(std::max(0, u1 - u0)),
        known_(stats_.size(), false) {}
  const ColumnStats& at(int u, int v0, int v1) {
    if (v0 != v0_ || v1 != v1_) std::fill(known_.begin(), known_.end(), false), v0_ = v0, v1_ = v1;
    const auto i = static_cast<size_t>(u - u0_);
    if (!known_[i]) stats_[i] = columnStats(disparity_, ground_, tol_, u, v0, v1, scratch_), known_[i] = true;
    return stats_[i];
  }

 private:
  const cv::Mat& disparity_;
  const GroundModel& ground_;
  float tol_;
  int u0_, v0_ = -1, v1_ = -1;
  std::vector<ColumnStats> stats_;
  std::vector<bool> known_;
  std::vector<float> scratch_;
};

}  // namespace

GapCut findGapColumns(const std::vector<const Stixel*>& group, const cv::Mat& disparity, const StereoCamera& cam,
                      const GroundModel& ground, const GapColumnParams& p) {
  GapCut none;
  const GapStripParams& e = p.ends;
  if (p.min_dip_px <= 0 || group.size() < 2 || disparity.empty() || !ground.valid) return none;
  const std::vector<const Stixel*> s = nearestPerStrip(group);
  const int n = static_cast<int>(s.size());
  const float fx = static_cast<float>(cam.fx);
  const int g0 = s.front()->u, g1 = s.back()->u + s.back()->width;  // the group's columns [g0, g1)
  ColumnCache columns(disparity, ground, p.ground_tolerance_m, g0, g1);
  std::vector<float> h, tops, bottoms;
  for (int from_left = 1; from_left >= 0; --from_left) {
    for (int k = std::max(1, e.min_end_stixels); k < n; ++k) {
      const int a = from_left ? 0 : n - k, b = from_left ? k : n;
      // The road user's end: its plateau is the median of its strips' disparities.
      const StripRun end = describeRun(s, static_cast<size_t>(a), static_cast<size_t>(b), cam, &ground);
      if (end.width_m > e.max_end_width_m) break;
      if (end.spread_px > e.max_spread_px) continue;
      const float end_h = end.median_h, plateau = end.median_d;
      if (end_h < e.min_height_m || end_h > e.max_height_m) continue;
      tops.clear(), bottoms.clear();
      for (int j = a; j < b; ++j) {
        tops.push_back(static_cast<float>(s[j]->top_row));
        bottoms.push_back(static_cast<float>(s[j]->bottom_row));
      }
      const size_t m = tops.size() / 2;
      std::nth_element(tops.begin(), tops.begin() + m, tops.end());
      std::nth_element(bottoms.begin(), bottoms.begin() + m, bottoms.end());
      const int v0 = std::max(0, static_cast<int>(tops[m]));
      const int v1 = std::min(disparity.rows - 1, static_cast<int>(bottoms[m]));
      if (v1 - v0 < 4) continue;
      const double z_end = cam.depthFromDisparity(plateau);
      auto farther = [&](float x) {
        return x > 0 && x <= plateau - p.min_dip_px && cam.depthFromDisparity(x) - z_end >= e.min_dip_m;
      };
      const int max_gap_px = static_cast<int>(std::floor(e.max_gap_m * fx / z_end));
      // Columns outward from the end's middle: the first run farther than the plateau.
      const int step = from_left ? 1 : -1;
      const int mid_u = (s[a]->u + s[b - 1]->u + s[b - 1]->width) / 2;
      auto inside = [&](int u) { return u >= g0 && u < g1 && u >= 0 && u < disparity.cols; };
      int u = mid_u, gap_first = -1, gap_last = -1;
      float deepest = 1e9f, background = 1e9f;
      bool hole = false;  // a column without enough pixels inside the run: a gap is measured, not a hole
      for (; inside(u); u += step) {
        const ColumnStats c = columns.at(u, v0, v1);
        const float x = c.median;
        if (gap_first < 0) {
          if (!farther(x)) continue;
          gap_first = u;
        } else if (!(x > 0)) {
          hole = true;
          break;
        } else if (!farther(x)) {
          break;
        }
        gap_last = u;
        deepest = std::min(deepest, x);
        background = std::min(background, c.q25 > 0 ? c.q25 : x);
        if (std::abs(gap_last - gap_first) + 1 > max_gap_px) break;
      }
      if (gap_first < 0 || hole) continue;  // no gap beside this end
      // The gap starts where the end's strips end: at most max_inside_px
      // within them (a dip deeper inside is the end's own shape, the space
      // between a far pedestrian's arm and body, urban seed 13 at 36-38 m on
      // the rendered disparity) and at most a strip beyond (one farther on
      // lies inside whatever the end belongs to).
      const int inner = from_left ? s[b - 1]->u + s[b - 1]->width : s[a]->u - 1;
      const int outward = (gap_first - inner) * step;
      if (outward < -p.max_inside_px || outward > s[a]->width) continue;
      if (std::abs(gap_last - gap_first) + 1 > max_gap_px) continue;  // a ramp or the background, not a gap
      // The far side, inside the group: within far_side_px it rises again
      // above the gap's deepest column (a run that reaches the group's end is
      // a side receding from the camera as likely as a gap), and it is not
      // the end's own surface going on past a dip (an untextured van's rear
      // reads a valley in its middle): its median lies off the plateau by
      // min_dip_px, it spreads over twice min_rise_px (a receding side), or
      // its strips' tops differ from the end's by min_height_step_m.
      std::vector<float> far;
      for (int q = 0; q < p.far_side_px && inside(u + step * q); ++q) {
        const float x = columns.at(u + step * q, v0, v1).median;
        if (x > 0) far.push_back(x);
      }
      if (far.empty()) continue;
      const auto [far_lo, far_hi] = std::minmax_element(far.begin(), far.end());
      if (*far_hi < deepest + p.min_rise_px) continue;
      const float spread = *far_hi - *far_lo;
      std::nth_element(far.begin(), far.begin() + far.size() / 2, far.end());
      // Or a remnant: the group ends within a strip after the gap (the near
      // end of a vehicle's side, cut off from the rest by the grouping).
      const bool remnant = !inside(u + step * s[a]->width);
      bool other = remnant || std::abs(far[far.size() / 2] - plateau) >= p.min_dip_px || spread >= 2 * p.min_rise_px;
      if (!other) {
        const int f0 = std::min(u, u + step * (p.far_side_px - 1)), f1 = std::max(u, u + step * (p.far_side_px - 1));
        h.clear();
        for (const Stixel* x : s)
          if (x->u <= f1 && x->u + x->width > f0) h.push_back(topHeightOverRoad(*x, cam, &ground));
        if (!h.empty()) {
          std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
          other = std::abs(h[h.size() / 2] - end_h) >= p.min_height_step_m;
        }
      }
      if (!other) continue;
      // Through a gap the background shows: a quarter of some gap column's
      // pixels lie min_background_m behind the end (a dip in a van's rear, or
      // a car's rear going over into its side, stays within a metre or two).
      if (!(background > 0) || cam.depthFromDisparity(background) - z_end < p.min_background_m) continue;
      GapCut c;
      c.found = true;
      // Each end strip stays on its side even when the gap starts inside it.
      c.lo = from_left ? std::max(gap_first, s[b - 1]->u + 1) : u + 1;
      c.hi = from_left ? u : std::min(gap_first + 1, s[a]->u);
      return c;
    }
  }
  return none;
}

}  // namespace nerv::stixel

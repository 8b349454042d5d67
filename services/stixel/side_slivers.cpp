#include "side_slivers.hpp"

#include <algorithm>

#include "height_steps.hpp"
#include "nearest_per_strip.hpp"
#include "upper_median.hpp"

namespace nerv::stixel {

namespace {

struct Extent {
  int x0 = 0, x1 = 0;        // columns [x0, x1)
  float near_m = 0, far_m = 0, median_m = 0;
  float top_m = 0;           // highest stixel top over the road
  float median_top_m = 0;    // median stixel top over the road (a vehicle's roof line)
  float visible_m = 0;       // from the highest stixel top to the lowest foot
  float top_spread_m = 0;    // interquartile range of the stixel tops over the road (a roof line: small)
  size_t strips = 0;
};

Extent extentOf(const std::vector<const Stixel*>& s, const StereoCamera& cam, const GroundModel* ground) {
  Extent e;
  e.x0 = s.front()->u, e.x1 = s.back()->u + s.back()->width;
  int top_row = s.front()->top_row, bottom_row = s.front()->bottom_row;
  e.near_m = e.far_m = s.front()->depth_m;
  std::vector<float> z, top;
  for (const Stixel* x : s) {
    e.near_m = std::min(e.near_m, x->depth_m), e.far_m = std::max(e.far_m, x->depth_m);
    top.push_back(topHeightOverRoad(*x, cam, ground));
    top_row = std::min(top_row, x->top_row), bottom_row = std::max(bottom_row, x->bottom_row);
    z.push_back(x->depth_m);
  }
  e.top_m = *std::max_element(top.begin(), top.end());
  e.median_m = upperMedian(z);
  std::sort(top.begin(), top.end());
  e.median_top_m = top[top.size() / 2];
  e.top_spread_m = top[(3 * top.size()) / 4] - top[top.size() / 4];
  e.visible_m = static_cast<float>((bottom_row - top_row + 1) * e.median_m / cam.fy);
  e.strips = s.size();
  return e;
}

}  // namespace

SliverAction sliverAction(const std::vector<const Stixel*>& sliver, const std::vector<const Stixel*>& host_group,
                          const StereoCamera& cam, const GroundModel* ground, const SideSliverParams& p) {
  constexpr SliverAction kNone = SliverAction::kNone;
  if (p.max_stixels <= 0 || sliver.empty() || host_group.empty()) return kNone;
  // Cheap first (called for every pair of groups): a sliver touches its host.
  auto columns = [](const std::vector<const Stixel*>& g, int& x0, int& x1) {
    x0 = g.front()->u, x1 = g.front()->u + g.front()->width;
    for (const Stixel* x : g) x0 = std::min(x0, x->u), x1 = std::max(x1, x->u + x->width);
  };
  int sx0, sx1, hx0, hx1;
  columns(sliver, sx0, sx1), columns(host_group, hx0, hx1);
  const int cw = std::max(1, p.column_width_px);
  const int reach = cw * std::max(1, p.tall_max_gap_strips);  // the widest gap allowed below
  if (sx0 > hx1 + reach || sx1 < hx0 - reach) return kNone;
  const std::vector<const Stixel*> s = nearestPerStrip(sliver);
  const Extent sl = extentOf(s, cam, ground);
  const std::vector<const Stixel*> h = nearestPerStrip(host_group);
  const Extent host = extentOf(h, cam, ground);
  // A tall host: a truck or a bus, taller than any road user, with a flat
  // roof line (a tree's crown or a sign's group is ragged).
  const bool tall_host = p.tall_host_m > 0 && host.median_top_m >= p.tall_host_m &&
                         host.top_spread_m <= p.tall_max_top_spread_m;
  const size_t max_strips = static_cast<size_t>(tall_host ? std::max(p.max_stixels, p.tall_max_stixels) : p.max_stixels);
  const float max_width_m = tall_host ? std::max(p.max_width_m, p.tall_max_width_m) : p.max_width_m;
  if (sl.strips > max_strips || (sl.x1 - sl.x0) * sl.median_m / cam.fx > max_width_m) return kNone;
  if (host.strips <= sl.strips || (host.x1 - host.x0) * host.median_m / cam.fx < p.min_host_width_m ||
      host.median_top_m < p.min_host_height_m || host.median_top_m > p.max_host_height_m)
    return kNone;
  // Beside the host towards the principal point, sticking out beyond its
  // edge and touching it (at most one empty strip between, or
  // tall_max_gap_strips beside a tall host).
  const int touch = cw * (tall_host ? std::max(1, p.tall_max_gap_strips) : 1);
  const double centre = 0.5 * (sl.x0 + sl.x1);
  const bool right = sl.x1 > host.x1 && sl.x0 > host.x0;
  const bool left = sl.x0 < host.x0 && sl.x1 < host.x1;
  if (!right && !left) return kNone;
  if (right && (centre > cam.cx || sl.x0 > host.x1 + touch)) return kNone;
  if (left && (centre < cam.cx || sl.x1 < host.x0 - touch)) return kNone;
  // Farther than the host's facing stixel, within a vehicle's length of its
  // nearest one (the length from the taller of the facing strip and the host).
  const Stixel& facing = right ? *h.back() : *h.front();
  const float facing_height_m = static_cast<float>((facing.bottom_row - facing.top_row + 1) * facing.depth_m / cam.fy);
  const float length_m = p.length_per_height * std::max(facing_height_m, host.visible_m);
  if (sl.near_m <= facing.depth_m || sl.far_m - host.near_m > std::max(p.max_depth_m, length_m)) return kNone;
  // Not taller than the vehicle (a road user beside it is): than its roof
  // line or the facing strip it continues, whichever is higher (a van's side
  // is as tall as its rear corner, which may stand above the median of lower strips).
  const float roof_m = std::max(host.median_top_m, topHeightOverRoad(facing, cam, ground));
  if (sl.top_m > roof_m + (tall_host ? p.tall_top_tolerance_m : p.top_tolerance_m)) return kNone;
  return sl.visible_m >= p.min_fold_share * host.visible_m ? SliverAction::kFold : SliverAction::kDrop;
}

}  // namespace nerv::stixel

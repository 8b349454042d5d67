#include "hypothesis_grouping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nearest_per_strip.hpp"
#include "stixel_height.hpp"

namespace nerv::stixel {

namespace {

constexpr int kNoSurround = std::numeric_limits<int>::max();

// Depth and lateral gap between two stixels (a left of b).
bool joins(const Stixel& a, const Stixel& b, const StereoCamera& cam, const GroupingParams& p) {
  const float dz = std::abs(a.depth_m - b.depth_m);
  const float z = std::min(a.depth_m, b.depth_m);
  const float gap_px = static_cast<float>(b.u - (a.u + a.width));
  const float lateral_m = std::max(0.0f, gap_px) * z / static_cast<float>(cam.fx);
  return dz <= p.group_depth_gap_m && lateral_m <= p.group_lateral_gap_m;
}

// Union-find root with path halving.
size_t root(std::vector<size_t>& parent, size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// A post or pole standing in a hedge, on a kerb or a lawn edge joins their
// group by depth, and the group's box (as wide as the hedge) then misses it.
// Runs of stixels (in u order) at least tower_min_height_m tall and
// tower_height_ratio times the group's median height, no wider than
// tower_max_width_m, leave the group as groups of their own; the rest of
// the group stays one group per contiguous part. Split-off towers are
// marked so that a one-stixel post is not dropped as too small, and they
// carry the top row of the stixels beside them (clear_above): below it the
// post stands in the hedge, at the hedge's depth, so only the rows above it
// show where the post's own edges are.
void splitTowers(std::vector<std::vector<const Stixel*>>& groups, std::vector<bool>& tower,
                 std::vector<int>& clear_above, const StereoCamera& cam, const GroupingParams& p) {
  if (p.tower_min_height_m <= 0) return;
  std::vector<std::vector<const Stixel*>> out;
  std::vector<bool> out_tower;
  std::vector<int> out_clear;
  std::vector<float> h;
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& g = groups[gi];
    if (g.size() < 2) {
      out.push_back(g), out_tower.push_back(tower[gi]), out_clear.push_back(clear_above[gi]);
      continue;
    }
    h.clear();
    for (const Stixel* s : g) h.push_back(stixelHeightM(*s, cam));
    std::vector<float> sorted = h;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const float median = sorted[sorted.size() / 2];
    const float need = std::max(p.tower_min_height_m, p.tower_height_ratio * median);
    std::vector<bool> is_tower(g.size());
    for (size_t k = 0; k < g.size(); ++k) is_tower[k] = h[k] >= need;
    // A lower stixel sharing its strip with a tower stixel (the lawn or kerb in
    // front of a post, seen below it) does not break the post's run: it leaves
    // the run's group and forms the companions' group of its own.
    auto besideTower = [&](size_t k) {  // a lower stixel in a strip that holds a tower stixel
      if (is_tower[k]) return false;
      for (size_t j = 0; j < g.size(); ++j)
        if (is_tower[j] && g[j]->u == g[k]->u) return true;
      return false;
    };
    std::vector<bool> companion(g.size(), false);
    if (p.tower_companions)
      for (size_t k = 0; k < g.size(); ++k) companion[k] = besideTower(k);
    std::vector<size_t> idx;  // the stixels that form runs, in u order
    for (size_t k = 0; k < g.size(); ++k)
      if (!companion[k]) idx.push_back(k);
    // Runs of towers; too wide a run is the object itself, not a post in it.
    bool any = false;
    for (size_t a = 0; a < idx.size();) {
      size_t e = a;
      while (e < idx.size() && is_tower[idx[e]] == is_tower[idx[a]]) ++e;
      if (is_tower[idx[a]]) {
        const Stixel& first = *g[idx[a]];
        const Stixel& last = *g[idx[e - 1]];
        const float width_m = (last.u + last.width - first.u) * first.depth_m / static_cast<float>(cam.fx);
        if (width_m > p.tower_max_width_m || (a == 0 && e == idx.size()))
          for (size_t j = a; j < e; ++j) is_tower[idx[j]] = false;
        else
          any = true;
      }
      a = e;
    }
    if (!any) {
      out.push_back(g), out_tower.push_back(tower[gi]), out_clear.push_back(clear_above[gi]);
      continue;
    }
    std::vector<const Stixel*> companions;
    for (size_t k = 0; k < g.size(); ++k)
      if (companion[k]) {
        if (besideTower(k)) companions.push_back(g[k]);
        else idx.insert(std::upper_bound(idx.begin(), idx.end(), k), k);  // its tower was too wide: back in line
      }
    for (size_t a = 0; a < idx.size();) {
      size_t e = a;
      while (e < idx.size() && is_tower[idx[e]] == is_tower[idx[a]]) ++e;
      out.emplace_back();
      for (size_t j = a; j < e; ++j) out.back().push_back(g[idx[j]]);
      out_tower.push_back(is_tower[idx[a]]);
      int clear = kNoSurround;
      if (is_tower[idx[a]]) {
        if (a > 0) clear = std::min(clear, g[idx[a - 1]]->top_row);
        if (e < idx.size()) clear = std::min(clear, g[idx[e]]->top_row);
      }
      out_clear.push_back(clear);
      a = e;
    }
    if (!companions.empty()) {
      out.push_back(companions), out_tower.push_back(false), out_clear.push_back(kNoSurround);
    }
  }
  groups.swap(out);
  tower.swap(out_tower);
  clear_above.swap(out_clear);
}

// A post that is half of a short hedge group is not twice the group's
// median (splitTowers); hedge_posts.hpp finds it by its neighbours instead.
// It leaves the group as a tower, like splitTowers' posts.
void splitHedgePosts(std::vector<std::vector<const Stixel*>>& groups, std::vector<bool>& tower,
                     std::vector<int>& clear_above, const StereoCamera& cam, const GroupingParams& p) {
  if (p.hedge_posts.min_ratio <= 0) return;
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    if (tower[gi]) continue;
    const auto [k, e] = findHedgePost(groups[gi], cam, p.hedge_posts);
    if (k == e) continue;
    const std::vector<const Stixel*> g = groups[gi];
    int clear = kNoSurround;
    if (k > 0) clear = std::min(clear, g[k - 1]->top_row);
    if (e < g.size()) clear = std::min(clear, g[e]->top_row);
    std::vector<std::vector<const Stixel*>> parts;
    std::vector<bool> part_tower;
    std::vector<int> part_clear;
    if (k > 0) parts.emplace_back(g.begin(), g.begin() + k), part_tower.push_back(false), part_clear.push_back(kNoSurround);
    parts.emplace_back(g.begin() + k, g.begin() + e), part_tower.push_back(true), part_clear.push_back(clear);
    if (e < g.size()) parts.emplace_back(g.begin() + e, g.end()), part_tower.push_back(false), part_clear.push_back(kNoSurround);
    groups.erase(groups.begin() + static_cast<long>(gi));
    tower.erase(tower.begin() + static_cast<long>(gi));
    clear_above.erase(clear_above.begin() + static_cast<long>(gi));
    groups.insert(groups.begin() + static_cast<long>(gi), parts.begin(), parts.end());
    tower.insert(tower.begin() + static_cast<long>(gi), part_tower.begin(), part_tower.end());
    clear_above.insert(clear_above.begin() + static_cast<long>(gi), part_clear.begin(), part_clear.end());
    gi += parts.size() - 1;  // the parts are not searched again
  }
}

// A pedestrian beside a tree trunk or a facade, or a car parked against a
// wall, is at the structure's depth and joins its group; the box then
// covers the tree's crown and is rejected as too tall, and the road user
// is lost. No road user is taller than structure_min_height_m (the
// tallest trucks are ~4 m), so a group holding stixels that tall and
// stixels lower than that is split into runs of each (in u order): the
// structure's box stays (the validator judges it), the road user gets its
// own. Runs too small for a hypothesis are dropped as before.
void splitStructures(std::vector<std::vector<const Stixel*>>& groups, std::vector<bool>& tower,
                     std::vector<int>& clear_above, const StereoCamera& cam, const GroupingParams& p) {
  if (p.structure_min_height_m <= 0) return;
  std::vector<std::vector<const Stixel*>> out;
  std::vector<bool> out_tower;
  std::vector<int> out_clear;
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& g = groups[gi];
    size_t tall = 0;
    for (const Stixel* s : g) tall += stixelHeightM(*s, cam) >= p.structure_min_height_m ? 1 : 0;
    if (tower[gi] || tall == 0 || tall == g.size()) {
      out.push_back(g), out_tower.push_back(tower[gi]), out_clear.push_back(clear_above[gi]);
      continue;
    }
    for (size_t k = 0; k < g.size();) {
      const bool is_tall = stixelHeightM(*g[k], cam) >= p.structure_min_height_m;
      size_t e = k + 1;
      while (e < g.size() && (stixelHeightM(*g[e], cam) >= p.structure_min_height_m) == is_tall) ++e;
      out.emplace_back(g.begin() + k, g.begin() + e);
      out_tower.push_back(false), out_clear.push_back(kNoSurround);
      k = e;
    }
  }
  groups.swap(out);
  tower.swap(out_tower);
  clear_above.swap(out_clear);
}

// Direction of a run of stixels: principal axis of their (X, Z) base points.
// Returns 1 for "along the road" (within ~27 deg of the optical axis), -1
// for "across" (within 45 deg of the image plane), 0 otherwise.
int runDirection(const std::vector<const Stixel*>& s, size_t a, size_t b, const StereoCamera& cam) {
  const double n = static_cast<double>(b - a);
  double mx = 0, mz = 0;
  std::vector<double> xs, zs;
  for (size_t k = a; k < b; ++k) {
    const double z = s[k]->depth_m, x = (s[k]->u + 0.5 * s[k]->width - cam.cx) * z / cam.fx;
    xs.push_back(x), zs.push_back(z), mx += x, mz += z;
  }
  mx /= n, mz /= n;
  double sxx = 0, szz = 0, sxz = 0;
  for (size_t k = 0; k < xs.size(); ++k)
    sxx += (xs[k] - mx) * (xs[k] - mx), szz += (zs[k] - mz) * (zs[k] - mz), sxz += (xs[k] - mx) * (zs[k] - mz);
  const double angle_deg = std::abs(0.5 * std::atan2(2 * sxz, sxx - szz)) * 180.0 / M_PI;  // from the X axis
  return angle_deg > 63.0 ? 1 : angle_deg < 45.0 ? -1 : 0;
}

// Strips s[a..b) without a gap between neighbours.
bool contiguousStrips(const std::vector<const Stixel*>& s, size_t a, size_t b) {
  for (size_t k = a + 1; k < b; ++k)
    if (s[k]->u - s[k - 1]->u > s[k - 1]->width) return false;
  return true;
}

// Where a receding run meets a face, when the direction test (runs of four
// read "along" then "across") cannot tell: beyond ~15 m four strips of a
// car's rear are 0.4 m wide with 0.2 m of depth noise and read "across" no
// better than "along", and the strip where rail and car meet mixes both. A
// vehicle's side recedes from its own rear and is as tall as the vehicle,
// so a run along the road that recedes towards a flat face (disparities
// within chain_face_max_spread_px) is another object when
//  - the face is nearer than the run's far end (the deeper of its last two
//    strips) by more than chain_reversal_min_jump_px: the run came back
//    towards the camera, which no vehicle's side does; or
//  - all strips of the face but one (the strip where they meet may still be
//    the rail's) stand chain_face_min_height_ratio times as tall as the
//    run's last four strips (median) and at least chain_face_min_height_m:
//    a guard rail or a kerb running up to a vehicle at its depth.
// c is the face's first strip (run on the left) or the run's first strip
// (face on the left); runs of four strips and of chain_long_run_stixels.
bool runEndsAtFace(const std::vector<const Stixel*>& s, size_t c, size_t face_run, const StereoCamera& cam,
                   const GroupingParams& p) {
  const bool by_jump = p.chain_reversal_min_jump_px > 0, by_height = p.chain_face_min_height_ratio > 0;
  if (!by_jump && !by_height) return false;
  auto contiguous = [&](size_t a, size_t b) { return contiguousStrips(s, a, b); };
  auto medianHeight = [&](size_t a, size_t b) {
    std::vector<float> h;
    for (size_t k = a; k < b; ++k) h.push_back(stixelHeightM(*s[k], cam));
    std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
    return h[h.size() / 2];
  };
  // face: strips [f0, f1); run: [r0, r1) with its far end at the face side.
  auto judge = [&](size_t f0, size_t f1, size_t r0, size_t r1, bool run_left) {
    float lo = s[f0]->disparity, hi = lo;
    for (size_t k = f0; k < f1; ++k) lo = std::min(lo, s[k]->disparity), hi = std::max(hi, s[k]->disparity);
    if (hi - lo > p.chain_face_max_spread_px) return false;
    const size_t end = run_left ? r1 - 1 : r0, start = run_left ? r0 : r1 - 1;
    const size_t next = run_left ? end - 1 : end + 1;
    const float far_d = std::min(s[end]->disparity, s[next]->disparity);
    if (!(far_d < s[start]->disparity)) return false;  // the run recedes towards the face
    if (by_jump && lo - far_d > p.chain_reversal_min_jump_px) return true;
    if (!by_height) return false;
    const size_t n = std::min<size_t>(4, r1 - r0);
    const float run_h = run_left ? medianHeight(r1 - n, r1) : medianHeight(r0, r0 + n);
    std::vector<float> fh;  // all strips of the face but one (its edge strip may still be the rail's)
    for (size_t k = f0; k < f1; ++k) fh.push_back(stixelHeightM(*s[k], cam));
    std::sort(fh.begin(), fh.end());
    const float face_h = fh[fh.size() > 1 ? 1 : 0];
    return face_h >= p.chain_face_min_height_m && face_h >= p.chain_face_min_height_ratio * run_h;
  };
  const size_t long_run = static_cast<size_t>(std::max(0, p.chain_long_run_stixels));
  for (const size_t run : {size_t(4), long_run}) {
    if (run < 4) continue;
    if (c >= run && c + face_run <= s.size() && contiguous(c - run, c + face_run) &&
        runDirection(s, c - run, c, cam) == 1 && judge(c, c + face_run, c - run, c, true))
      return true;
    if (c >= face_run && c + run <= s.size() && contiguous(c - face_run, c + run) &&
        runDirection(s, c, c + run, cam) == 1 && judge(c - face_run, c, c, c + run, false))
      return true;
  }
  return false;
}

// Surfaces along the road (a guard rail, a wall, a car's side) recede at a
// nearly constant lateral offset X, faces across it (a car's rear, a
// pedestrian) at a nearly constant depth Z. A receding surface that ends
// at a face joins it by depth, and a group too deep for one vehicle is such
// a chain: a guard rail running up to the car in front of it, a parked
// car's side running up to the next car's rear. A surface recedes away from
// the face it belongs to (a car's side from its own rear), so a face at the
// far end of a receding run is another object: the group is cut before it.
void splitChains(std::vector<std::vector<const Stixel*>>& groups, std::vector<bool>& tower,
                 std::vector<int>& clear_above, const StereoCamera& cam, const GroupingParams& p) {
  if (!p.split_chains) return;
  constexpr size_t kRun = 4;  // stixels on each side of a cut
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& g = groups[gi];
    if (tower[gi] || g.size() < 2 * kRun) continue;
    // One stixel per strip (the nearest), contiguous strips only.
    const std::vector<const Stixel*> s = nearestPerStrip(g);
    if (s.size() < 2 * kRun) continue;
    float zmin = s[0]->depth_m, zmax = zmin;
    std::vector<float> h;
    for (const Stixel* x : s) zmin = std::min(zmin, x->depth_m), zmax = std::max(zmax, x->depth_m), h.push_back(stixelHeightM(*x, cam));
    std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
    if (zmax - zmin <= std::max(p.side_max_depth_m, p.side_length_per_height * h[h.size() / 2])) continue;
    auto contiguousRun = [&](size_t a, size_t b) { return contiguousStrips(s, a, b); };
    const size_t long_run = static_cast<size_t>(std::max(0, p.chain_long_run_stixels));
    int cut_u = -1;
    for (size_t c = kRun; c + kRun <= s.size() && cut_u < 0; ++c) {
      if (!contiguousRun(c - kRun, c + kRun)) continue;
      const int face_left = runDirection(s, c - kRun, c, cam), right = runDirection(s, c, c + kRun, cam);
      // Along-road run receding towards the face it meets. Beyond ~15 m a
      // rail recedes ~0.5 m per strip, within the depth noise of four strips:
      // when those do not decide, a longer run before the face does.
      int left = face_left;
      size_t lrun = kRun;
      if (left != 1 && right == -1 && long_run > kRun && c >= long_run && contiguousRun(c - long_run, c))
        left = runDirection(s, c - long_run, c, cam), lrun = long_run;
      const bool rail_then_face = left == 1 && right == -1 && s[c - 1]->depth_m > s[c - lrun]->depth_m;
      const bool face_then_rail = face_left == -1 && right == 1 && s[c]->depth_m > s[c + kRun - 1]->depth_m;
      if (rail_then_face || face_then_rail || runEndsAtFace(s, c, kRun, cam, p))
        cut_u = s[c]->u;
    }
    if (cut_u < 0) continue;
    std::vector<const Stixel*> a, b;
    for (const Stixel* x : g) (x->u < cut_u ? a : b).push_back(x);
    groups[gi] = a;
    groups.insert(groups.begin() + static_cast<long>(gi) + 1, b);
    tower.insert(tower.begin() + static_cast<long>(gi) + 1, false);
    clear_above.insert(clear_above.begin() + static_cast<long>(gi) + 1, kNoSurround);
    --gi;  // the left part may hold another chain
  }
}

// The side of a vehicle seen at a grazing angle recedes by metres per strip
// (a face parallel to the optical axis at lateral offset X changes depth by
// z^2/(fx*|X|) per pixel column), so beyond ~15 m its one or two strips split
// from the vehicle's rear by depth and become a box of their own. A group of
// at most side_max_stixels strips joins a larger group it touches when it is
// shaped like such a side:
//  - it lies towards the principal point from the body: a face parallel to
//    the optical axis projects towards the vanishing point as it recedes, so
//    a "side" on the outward side is another object (a post, a pedestrian);
//  - it recedes monotonically, starting behind the body's facing stixel, and
//    its far end is at most side_length_per_height times the facing
//    stixel's height behind the body's nearest stixel: a vehicle is at most
//    about 4 times as long as it is tall (car 4.5 / 1.5 m, truck 9 / 3.6 m,
//    bus 12 / 3.2 m), so the next car of a parked row, which starts a gap
//    beyond the first car's front, stays a box of its own;
//  - it continues the body's silhouette: its top row within
//    side_top_tolerance of the facing stixel's pixel height.
void joinSides(std::vector<std::vector<const Stixel*>>& groups, std::vector<bool>& tower,
               std::vector<int>& clear_above, const StereoCamera& cam, const GroupingParams& p) {
  if (p.side_max_stixels <= 0) return;
  const int cw = std::max(1, p.column_width_px);
  const double cx = cam.cx;
  auto centre = [](const Stixel* s) { return s->u + 0.5 * s->width; };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < groups.size() && !changed; ++i) {
      auto& side = groups[i];
      if (side.empty() || static_cast<int>(side.size()) > p.side_max_stixels || tower[i]) continue;
      for (size_t j = 0; j < groups.size() && !changed; ++j) {
        auto& body = groups[j];
        if (j == i || body.size() <= side.size() || tower[j]) continue;
        // Facing stixels: body's last and side's first (side to the right), or the reverse.
        const Stixel* b = nullptr;
        const Stixel* s = nullptr;
        bool right = false;
        if (side.front()->u == body.back()->u + body.back()->width || side.front()->u == body.back()->u + cw)
          b = body.back(), s = side.front(), right = true;
        else if (body.front()->u == side.back()->u + side.back()->width || body.front()->u == side.back()->u + cw)
          b = body.front(), s = side.back();
        if (!b) continue;
        // Towards the principal point: a side right of its body lies left of cx, and vice versa.
        if (right ? centre(side.back()) > cx : centre(side.front()) < cx) continue;
        // Receding: each stixel farther than the one before it, from the body outwards.
        bool recedes = s->depth_m > b->depth_m;
        float far_m = s->depth_m;
        for (size_t k = 1; k < side.size() && recedes; ++k) {
          const Stixel* nearer = right ? side[k - 1] : side[side.size() - k];
          const Stixel* farther = right ? side[k] : side[side.size() - k - 1];
          recedes = farther->depth_m > nearer->depth_m;
          far_m = std::max(far_m, farther->depth_m);
        }
        // Measured from the body's nearest stixel, so that sides joined one
        // after the other cannot chain a parked row into one box.
        float near_m = b->depth_m;
        for (const Stixel* x : body) near_m = std::min(near_m, x->depth_m);
        const int height_px = b->bottom_row - b->top_row + 1;
        const float max_length_m = std::max(p.side_max_depth_m, p.side_length_per_height * stixelHeightM(*b, cam));
        if (!recedes || far_m - near_m > max_length_m ||
            std::abs(s->top_row - b->top_row) > p.side_top_tolerance * height_px)
          continue;
        body.insert(body.end(), side.begin(), side.end());
        std::sort(body.begin(), body.end(), [](const Stixel* x, const Stixel* y) { return x->u < y->u; });
        groups.erase(groups.begin() + static_cast<long>(i));
        tower.erase(tower.begin() + static_cast<long>(i));
        clear_above.erase(clear_above.begin() + static_cast<long>(i));
        changed = true;
      }
    }
  }
}

}  // namespace

std::vector<Hypothesis> groupStixels(const std::vector<Stixel>& stixels, const StereoCamera& cam,
                                     const GroupingParams& p, const GroupingInput& input) {
  // Stixels join when their depth and lateral gaps are small - across empty
  // strips (no valid disparity inside an object), and across at most one
  // occupied strip: a stray stixel (a window, a reflection, a thin post in
  // front) does not cut an object in two. Two stixels of the same strip (an
  // occluder and the object above it) never join directly.
  // Own copy: the overhang cut lowers stixel tops.
  std::vector<Stixel> own = stixels;
  std::vector<size_t> order(own.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return own[x].u < own[y].u; });
  std::vector<int> strip(order.size());  // rank of the stixel's column among occupied columns
  for (size_t k = 0; k < order.size(); ++k)
    strip[k] = k == 0 ? 0 : strip[k - 1] + (own[order[k]].u != own[order[k - 1]].u ? 1 : 0);
  std::vector<size_t> parent(own.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  for (size_t oi = 0; oi < order.size(); ++oi) {
    for (size_t oj = oi + 1; oj < order.size() && strip[oj] - strip[oi] <= 2; ++oj) {
      if (strip[oj] == strip[oi]) continue;
      if (joins(own[order[oi]], own[order[oj]], cam, p)) parent[root(parent, order[oi])] = root(parent, order[oj]);
    }
  }
  std::vector<std::vector<const Stixel*>> groups;
  std::vector<int> group_of(own.size(), -1);
  for (size_t i : order) {  // members in u order, groups in order of their leftmost stixel
    const size_t r = root(parent, i);
    if (group_of[r] < 0) group_of[r] = static_cast<int>(groups.size()), groups.emplace_back();
    groups[group_of[r]].push_back(&own[i]);
  }

  std::vector<bool> tower(groups.size(), false);
  std::vector<int> clear_above(groups.size(), kNoSurround);
  splitTowers(groups, tower, clear_above, cam, p);
  splitHedgePosts(groups, tower, clear_above, cam, p);
  splitStructures(groups, tower, clear_above, cam, p);
  splitChains(groups, tower, clear_above, cam, p);
  joinSides(groups, tower, clear_above, cam, p);

  // Road users beside a vehicle at about its depth (a height step, or the
  // matcher's blend in the background gap between them), and two pedestrians
  // side by side; after the joins, so a
  // vehicle's side cannot bring the cut part back. Each part's box stays on
  // its side of the cut (the refinement would otherwise extend it over the
  // other part's columns, which are at its depth).
  std::vector<int> min_x(groups.size(), std::numeric_limits<int>::min());
  std::vector<int> max_x(groups.size(), std::numeric_limits<int>::max());
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    if (tower[gi]) continue;
    int cut_u = findHeightStep(groups[gi], cam, input.ground, p.height_steps);
    // A background gap's strips [lo, hi) are dropped from both parts (gap_strips.hpp),
    // and so is the blended strip between two pedestrians (person_pairs.hpp).
    int lo = cut_u, hi = cut_u;
    if (cut_u < 0) {
      const GapCut pair = findPersonPair(groups[gi], cam, input.ground, p.person_pairs);
      if (pair.found) cut_u = lo = pair.lo, hi = pair.hi;
    }
    if (cut_u < 0) {
      GapCut gap = findGapStrips(groups[gi], cam, input.ground, p.gap_strips);
      if (!gap.found && input.disparity && input.ground)
        gap = findGapColumns(groups[gi], *input.disparity, cam, *input.ground, p.gap_columns);
      if (!gap.found) continue;
      lo = gap.lo, hi = gap.hi;
    }
    std::vector<const Stixel*> a, b;
    for (const Stixel* x : groups[gi])
      if (x->u < lo) a.push_back(x);
      else if (x->u >= hi) b.push_back(x);
    if (a.empty() || b.empty()) {  // the gap ran to the group's end: only the road user is left
      groups[gi] = a.empty() ? b : a;
      if (a.empty()) min_x[gi] = hi;
      else max_x[gi] = lo;
      continue;
    }
    groups[gi] = a;
    groups.insert(groups.begin() + static_cast<long>(gi) + 1, b);
    tower.insert(tower.begin() + static_cast<long>(gi) + 1, false);
    clear_above.insert(clear_above.begin() + static_cast<long>(gi) + 1, kNoSurround);
    min_x.insert(min_x.begin() + static_cast<long>(gi) + 1, hi);
    max_x.insert(max_x.begin() + static_cast<long>(gi) + 1, max_x[gi]);
    max_x[gi] = lo;
    ++gi;  // the right part is not cut again
  }

  // Slivers of a vehicle's receding side fold into it or are dropped
  // (side_slivers.hpp); after the cuts, and never a part they cut off (a road
  // user beside a car) nor into one, so they cannot undo them.
  auto wasCut = [&](size_t k) {
    return min_x[k] != std::numeric_limits<int>::min() || max_x[k] != std::numeric_limits<int>::max();
  };
  // Pieces stacked on a vehicle's roof line (roof_pieces.hpp) are dropped the same way.
  for (bool changed = p.side_slivers.max_stixels > 0 || p.roof_pieces.max_stixels > 0; changed;) {
    changed = false;
    for (size_t i = 0; i < groups.size() && !changed; ++i) {
      if (tower[i] || wasCut(i) || static_cast<int>(groups[i].size()) < std::max(1, p.min_stixels_per_hypothesis))
        continue;
      for (size_t j = 0; j < groups.size() && !changed; ++j) {
        if (j == i || tower[j] || wasCut(j)) continue;
        SliverAction action = sliverAction(groups[i], groups[j], cam, input.ground, p.side_slivers);
        if (action == SliverAction::kNone && isRoofPiece(groups[i], groups[j], cam, input.ground, p.roof_pieces))
          action = SliverAction::kDrop;
        if (action == SliverAction::kNone) continue;
        if (action == SliverAction::kFold) {
          groups[j].insert(groups[j].end(), groups[i].begin(), groups[i].end());
          std::sort(groups[j].begin(), groups[j].end(), [](const Stixel* x, const Stixel* y) { return x->u < y->u; });
        }
        const auto at = static_cast<long>(i);
        groups.erase(groups.begin() + at), tower.erase(tower.begin() + at), clear_above.erase(clear_above.begin() + at);
        min_x.erase(min_x.begin() + at), max_x.erase(max_x.begin() + at);
        changed = true;
      }
    }
  }

  // Tops lowered last, each group on its own stixels: below an overhang (a
  // tree's trunk must still be a structure when the structure split runs, or
  // the pedestrian beside it stays in its group), then below a layer just
  // behind a wide group's top (layered_tops.hpp; not a tower's).
  const bool overhangs = p.overhang.min_reach_m > 0, layers = p.layer_tops.min_separation_m > 0;
  if ((overhangs || layers) && input.disparity && input.ground) {
    std::vector<Stixel*> m;
    for (size_t gi = 0; gi < groups.size(); ++gi) {
      m.clear();
      for (const Stixel* s : groups[gi]) m.push_back(&own[static_cast<size_t>(s - own.data())]);
      if (overhangs) cutOverhang(*input.disparity, cam, *input.ground, m, p.overhang);
      if (layers && !tower[gi]) lowerLayeredTops(*input.disparity, cam, *input.ground, m, p.layer_tops);
    }
  }

  std::vector<Hypothesis> out;
  std::vector<float> disp;
  // One hypothesis from group g (its box refined within [group_min_x, group_max_x)).
  auto emit = [&](const std::vector<const Stixel*>& g, bool is_tower, int surround, int group_min_x,
                  int group_max_x) {
    if (!is_tower && static_cast<int>(g.size()) < std::max(1, p.min_stixels_per_hypothesis)) {
      // A lone tall stixel is a post or a sign, not noise.
      const Stixel& s = *g.front();
      const bool tall_single = g.size() == 1 && p.min_single_stixel_height_m > 0 &&
                               (s.bottom_row - s.top_row + 1) * s.depth_m / cam.fy >= p.min_single_stixel_height_m;
      const bool post = g.size() == 1 && input.posts &&
                        std::any_of(input.posts->begin(), input.posts->end(), [&](const Stixel& x) {
                          return x.u == s.u && x.top_row == s.top_row && x.disparity == s.disparity;
                        });
      if (!tall_single && !post) return;
    }
    if (!is_tower && isLowRun(g, cam, p.low_runs)) return;  // a rail or kerb along the road (low_runs.hpp)
    int x0 = g.front()->u, x1 = g.front()->u + g.front()->width;
    int y0 = g.front()->top_row, y1 = g.front()->bottom_row;
    disp.clear();
    for (const Stixel* s : g) {
      x0 = std::min(x0, s->u);
      x1 = std::max(x1, s->u + s->width);
      y0 = std::min(y0, s->top_row);
      y1 = std::max(y1, s->bottom_row);
      disp.push_back(s->disparity);
    }
    if (p.refine_boxes && input.disparity && input.ground) {
      PixelBox box{x0, x1, y0, y1};
      refineBox(*input.disparity, cam, *input.ground, g, p.column_width_px, p.refinement, box,
                p.tower_edges_above_surround ? surround : kNoSurround, group_min_x, group_max_x);
      widenPostSides(*input.disparity, cam, *input.ground, g, p.post_sides, box);
      raiseToHolePlate(*input.disparity, cam, *input.ground, g, p.hole_plates, box);
      extendOverOccluders(*input.disparity, cam, *input.ground, g, p.occluded_sides, box, group_min_x, group_max_x);
      raiseBlendedTop(*input.disparity, cam, *input.ground, g, p.blended_top, box);
      box.x0 = std::max(box.x0, group_min_x);
      box.x1 = std::min(box.x1, group_max_x);
      x0 = box.x0, x1 = box.x1, y0 = box.y0;
    }
    // Nearest part (what a planner keeps its distance from): the 90th
    // percentile of the stixels' disparities, the largest for groups of up to
    // six; the median below stays the box's representative depth. On the
    // synthetic sets it halves the error against the labels' nearest corner
    // (docs/detection_quality.md "Distance of the detections").
    std::sort(disp.begin(), disp.end());
    const float d_near = disp[std::min(disp.size() - 1, static_cast<size_t>(0.9 * (disp.size() - 1) + 0.5))];
    // Representative disparity: the median stixel (robust to one wrong stixel).
    const float d = disp[disp.size() / 2];
    const double z = cam.depthFromDisparity(d);
    // Base centre: the box's middle column on the ground below the median
    // stixel (its foot may be hidden behind an occluder: from the road line).
    double foot_v = 0;
    for (const Stixel* s : g)
      if (s->disparity == d) foot_v = s->bottom_row;
    if (input.ground && input.ground->valid && input.ground->vd_slope > 0 && input.disparity) {
      const double ground_foot = (d - input.ground->vd_intercept) / input.ground->vd_slope;
      if (ground_foot > foot_v + 1) foot_v = std::min(ground_foot, input.disparity->rows - 1.0);
    }
    const Point3 base = cam.toPoint(0.5 * (x0 + x1), foot_v, d);

    Hypothesis hy;
    hy.box = {x0, y0, x1 - x0, y1 - y0 + 1};
    hy.x_m = static_cast<float>(base.x);
    hy.y_m = static_cast<float>(base.y);
    hy.z_m = static_cast<float>(base.z);
    hy.width_m = static_cast<float>((x1 - x0) * z / cam.fx);
    hy.height_m = static_cast<float>((y1 - y0 + 1) * z / cam.fy);
    hy.distance_m =
        static_cast<float>(std::sqrt(base.x * base.x + base.y * base.y + base.z * base.z));
    hy.disparity = d;
    hy.num_stixels = static_cast<int>(g.size());
    hy.nearest_z_m = static_cast<float>(cam.depthFromDisparity(d_near));
    // z = f B / d, so a disparity error s gives dz = z^2 s / (f B) = z s / d.
    hy.nearest_z_sigma_m = d_near > 0 ? hy.nearest_z_m * p.depth_sigma_px / d_near : 0.0f;
    if (hy.height_m < p.min_obstacle_height_m || hy.distance_m > p.max_distance_m) return;
    out.push_back(hy);
  };
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    emit(groups[gi], tower[gi], clear_above[gi], min_x[gi], max_x[gi]);
    // A lower road user in front of a taller one in the same group gets a box of
    // its own too (nearer_fronts.hpp); the group's box stays the taller one's.
    if (tower[gi] || !input.ground) continue;
    const std::vector<const Stixel*> front = findNearerFront(groups[gi], cam, *input.ground, p.nearer_fronts);
    if (!front.empty())
      emit(front, false, kNoSurround, std::max(min_x[gi], front.front()->u),
           std::min(max_x[gi], front.back()->u + front.back()->width));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.box.x < b.box.x; });
  for (size_t i = 0; i < out.size(); ++i) out[i].id = static_cast<int>(i);
  return out;
}

}  // namespace nerv::stixel

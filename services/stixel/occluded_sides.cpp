#include "occluded_sides.hpp"

#include <algorithm>
#include <cmath>

#include "disparity_tolerance.hpp"
#include "ground_geometry.hpp"

namespace nerv::stixel {
namespace {


struct Column {
  const cv::Mat& disp;
  const GroundModel& ground;
  float ground_tol_m;
  float at(int v, int u) const { return disp.ptr<float>(v)[u]; }
  bool valid(float x) const { return std::isfinite(x) && x > 0; }
};

// Does column u continue the object of disparity d over a nearer occluder?
bool continues(const Column& c, int u, int band_top, int half, int bottom, float d, float tol, float nearer,
               const OccludedSideParams& p) {
  // The occluder's top: the first valid nearer pixel whose next valid pixel is
  // nearer too, in the box's upper half (it hides the object's lower part).
  int occ_top = -1;
  for (int v = band_top; v <= half && occ_top < 0; ++v) {
    const float x = c.at(v, u);
    if (!c.valid(x) || x <= nearer) continue;
    for (int w = v + 1; w <= bottom; ++w) {
      const float y = c.at(w, u);
      if (!c.valid(y)) continue;
      if (y > nearer) occ_top = v;
      break;
    }
  }
  if (occ_top <= band_top) return false;  // no occluder, or nothing visible above it
  // The occluder hides the object's lower part: most valid pixels from its top down are nearer.
  int hidden = 0, below = 0;
  for (int v = occ_top; v <= bottom; ++v) {
    const float x = c.at(v, u);
    if (!c.valid(x)) continue;
    ++below;
    hidden += x > nearer ? 1 : 0;
  }
  if (2 * hidden < below) return false;
  int at_depth = 0, valid = 0;
  for (int v = band_top; v < occ_top; ++v) {
    const float x = c.at(v, u);
    if (!c.valid(x)) continue;
    ++valid;
    if (std::fabs(x - d) <= tol && heightAboveGround(c.ground, static_cast<float>(v), x) > c.ground_tol_m) ++at_depth;
  }
  return at_depth >= p.min_pixels && at_depth >= p.min_fill * valid;
}

}  // namespace

bool extendOverOccluders(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                         const std::vector<const Stixel*>& group, const OccludedSideParams& p, PixelBox& box,
                         int min_x, int max_x) {
  if (p.max_extension_m <= 0 || group.empty() || disparity.empty() || box.x1 <= box.x0) return false;
  const float depth = group.front()->depth_m;
  if (!(depth > 0) || (box.x1 - box.x0) * depth / cam.fx < p.min_width_m ||
      (box.y1 - box.y0 + 1) * depth / cam.fy > p.max_height_m)
    return false;
  const Column c{disparity, ground, p.ground_tolerance_m};
  const int lo_x = std::max(0, min_x), hi_x = std::min(disparity.cols, max_x);
  const int bottom = std::min(box.y1, disparity.rows - 1);
  const int half = (box.y0 + bottom) / 2;
  bool moved = false;
  for (const int dir : {+1, -1}) {
    const Stixel& s = dir > 0 ? *group.back() : *group.front();
    if (!(s.depth_m > 0)) continue;
    const float tol = disparityTolerance(s.disparity, cam, p.depth_tolerance_m);
    // Nearer than the object's own tolerance band by the step (a neighbour within the band is beside it, not in front).
    const float nearer = s.disparity + tol + disparityTolerance(s.disparity, cam, p.min_depth_step_m);
    const int band_top = std::max(0, box.y0 - static_cast<int>(p.search_above_m * cam.fy / s.depth_m));
    const int reach = static_cast<int>(p.max_extension_m * cam.fx / s.depth_m);
    const int max_gap = static_cast<int>(p.max_gap_m * cam.fx / s.depth_m);
    const int start = dir > 0 ? box.x1 : box.x0 - 1;  // first column outside the box
    int last = -1, gap = 0;
    for (int k = 0; k < reach; ++k) {
      const int u = start + dir * k;
      if (u < lo_x || u >= hi_x) break;
      if (continues(c, u, band_top, half, bottom, s.disparity, tol, nearer, p)) {
        last = u;
        gap = 0;
      } else if (++gap > max_gap) {
        break;
      }
    }
    if (last < 0) continue;
    if (dir > 0) box.x1 = last + 1;
    else box.x0 = last;
    moved = true;
  }
  return moved;
}

}  // namespace nerv::stixel

#include "roof_pieces.hpp"

#include <algorithm>
#include <cstdlib>

#include "height_steps.hpp"
#include "nearest_per_strip.hpp"

namespace nerv::stixel {

bool isRoofPiece(const std::vector<const Stixel*>& piece, const std::vector<const Stixel*>& host_group,
                 const StereoCamera& cam, const GroundModel* ground, const RoofPieceParams& p) {
  if (p.max_stixels <= 0 || piece.empty() || host_group.empty()) return false;
  // Cheap first (called for every pair of groups): every strip of the piece is one of the host's.
  auto columns = [](const std::vector<const Stixel*>& g, int& x0, int& x1) {
    x0 = g.front()->u, x1 = g.front()->u;
    for (const Stixel* x : g) x0 = std::min(x0, x->u), x1 = std::max(x1, x->u);
  };
  int px0, px1, hx0, hx1;
  columns(piece, px0, px1), columns(host_group, hx0, hx1);
  if (px0 < hx0 || px1 > hx1) return false;
  const std::vector<const Stixel*> strips = nearestPerStrip(piece);
  const std::vector<const Stixel*> host = nearestPerStrip(host_group);
  if (strips.size() > static_cast<size_t>(p.max_stixels) || host.size() <= strips.size()) return false;
  // The host is a vehicle: wide enough, its roof line at a vehicle's height.
  std::vector<float> z, top;
  int top_row = host.front()->top_row;
  for (const Stixel* x : host) {
    z.push_back(x->depth_m), top.push_back(topHeightOverRoad(*x, cam, ground));
    top_row = std::min(top_row, x->top_row);
  }
  std::nth_element(z.begin(), z.begin() + z.size() / 2, z.end());
  std::nth_element(top.begin(), top.begin() + top.size() / 2, top.end());
  const int x0 = host.front()->u, x1 = host.back()->u + host.back()->width;
  if ((x1 - x0) * z[z.size() / 2] / cam.fx < p.min_host_width_m || top[top.size() / 2] < p.min_host_height_m ||
      top[top.size() / 2] > p.max_host_height_m)
    return false;
  // Every stixel stands on one of the host's in its strip, farther by at most
  // a car's length, and none reaches above the host's top.
  for (const Stixel* s : piece) {
    if (s->top_row < top_row - p.top_tolerance_px) return false;
    const bool on_host = std::any_of(host_group.begin(), host_group.end(), [&](const Stixel* h) {
      return h->u == s->u && std::abs(h->top_row - 1 - s->bottom_row) <= p.max_gap_px && s->depth_m > h->depth_m &&
             s->depth_m - h->depth_m <= p.max_depth_m;
    });
    if (!on_host) return false;
  }
  return true;
}

}  // namespace nerv::stixel

#include "nearer_fronts.hpp"

#include <algorithm>
#include <map>

#include "ground_geometry.hpp"

namespace nerv::stixel {

std::vector<const Stixel*> findNearerFront(const std::vector<const Stixel*>& group, const StereoCamera& cam,
                                           const GroundModel& ground, const NearerFrontParams& p) {
  if (p.min_step_m <= 0 || group.size() < 3 || !ground.valid) return {};
  std::map<int, const Stixel*> lowest;  // first layer: the lowest stixel of each strip
  for (const Stixel* s : group) {
    auto [it, fresh] = lowest.emplace(s->u, s);
    if (!fresh && s->bottom_row > it->second->bottom_row) it->second = s;
  }
  // The near and the far part: split the first layer's disparities at their widest gap.
  std::vector<float> d;
  for (const auto& [u, s] : lowest) d.push_back(s->disparity);
  if (d.size() < 3) return {};
  std::sort(d.begin(), d.end());
  size_t cut = 0;
  for (size_t i = 1; i + 1 < d.size(); ++i)
    if (d[i + 1] - d[i] > d[cut + 1] - d[cut]) cut = i;
  const float far = d[cut], near = d[cut + 1];
  if (!(far > 0)) return {};
  // Nearer by min_step_m at the far part's depth, and by min_step_px.
  const double z = cam.depthFromDisparity(far);
  if (!(z > p.min_step_m)) return {};
  const float need = std::max(p.min_step_px, static_cast<float>(cam.disparityFromDepth(z - p.min_step_m) - far));
  if (near - far < need) return {};
  auto heightOf = [&](const Stixel* s) {  // top over the road [m]
    return heightAboveGround(ground, static_cast<float>(s->top_row), s->disparity);
  };
  std::vector<const Stixel*> best, run;
  auto close = [&] {
    if (static_cast<int>(run.size()) > static_cast<int>(best.size())) best = run;
    run.clear();
  };
  for (const auto& [u, s] : lowest) {
    const bool front = s->disparity >= near && heightOf(s) <= p.max_height_m;
    if (front && !run.empty() && u != run.back()->u + run.back()->width) close();  // a gap between strips
    if (front) run.push_back(s);
    else close();
  }
  close();
  if (static_cast<int>(best.size()) < std::max(1, p.min_strips)) return {};
  float front_top = 0, rest_top = 0;
  std::vector<float> tops;
  for (const Stixel* s : best) front_top = std::max(front_top, heightOf(s)), tops.push_back(heightOf(s));
  std::nth_element(tops.begin(), tops.begin() + tops.size() / 2, tops.end());
  const float front_median_top = tops[tops.size() / 2];
  int rest = 0;
  for (const Stixel* s : group)
    if (std::find(best.begin(), best.end(), s) == best.end()) rest_top = std::max(rest_top, heightOf(s)), ++rest;
  if (front_median_top < p.min_height_m || rest < 2 || rest_top < front_top + p.min_rise_m) return {};
  return best;
}

}  // namespace nerv::stixel

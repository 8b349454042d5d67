#include "distance_accuracy.hpp"

#include "percentile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nerv {

float labelNearestDepth(const KittiLabel& l) {
  if (!(l.z > 0) || !std::isfinite(l.z)) return 0;
  if (!(l.l > 0 && l.w > 0) || l.x < -999) return l.z;
  const float c = std::cos(l.rotation_y), s = std::sin(l.rotation_y);
  float nearest = l.z;
  for (const float dx : {-0.5f * l.l, 0.5f * l.l})
    for (const float dz : {-0.5f * l.w, 0.5f * l.w}) nearest = std::min(nearest, l.z - s * dx + c * dz);
  return nearest;
}

bool labelDepthComparable(const KittiLabel& l) {
  return l.truncated <= 0 && l.occluded == 0 && labelNearestDepth(l) > 0;
}

void DistanceAccuracy::add(float truth_m, float estimate_m, float sigma_m) {
  if (!(truth_m > 0) || !(estimate_m > 0) || !std::isfinite(truth_m) || !std::isfinite(estimate_m)) return;
  truth_.push_back(truth_m);
  estimate_.push_back(estimate_m);
  sigma_.push_back(sigma_m > 0 && std::isfinite(sigma_m) ? sigma_m : 0.0f);
}


std::vector<DistanceErrorBand> DistanceAccuracy::bands(const std::vector<float>& edges) const {
  std::vector<DistanceErrorBand> out;
  for (size_t b = 0; b < edges.size(); ++b) {
    DistanceErrorBand band;
    band.from_m = edges[b];
    band.to_m = b + 1 < edges.size() ? edges[b + 1] : INFINITY;
    std::vector<double> abs_err, rel_err, over_sigma;
    double sum = 0;
    for (size_t i = 0; i < truth_.size(); ++i) {
      if (truth_[i] < band.from_m || truth_[i] >= band.to_m) continue;
      const double e = static_cast<double>(estimate_[i]) - truth_[i];
      sum += e;
      abs_err.push_back(std::fabs(e));
      rel_err.push_back(std::fabs(e) / truth_[i]);
      if (sigma_[i] > 0) over_sigma.push_back(std::fabs(e) / sigma_[i]);
    }
    if (abs_err.empty()) continue;
    band.count = static_cast<int>(abs_err.size());
    band.bias_m = sum / band.count;
    band.median_abs_m = percentile(abs_err, 0.5);
    band.p95_abs_m = percentile(abs_err, 0.95);
    band.median_rel = percentile(rel_err, 0.5);
    if (!over_sigma.empty()) {
      band.count_with_sigma = static_cast<int>(over_sigma.size());
      const auto share = [&](double k) {
        return static_cast<double>(std::count_if(over_sigma.begin(), over_sigma.end(),
                                                 [k](double r) { return r <= k; })) /
               static_cast<double>(over_sigma.size());
      };
      band.within_1sigma = share(1.0);
      band.within_2sigma = share(2.0);
      band.p68_abs_over_sigma = percentile(over_sigma, 0.68);
    }
    out.push_back(band);
  }
  return out;
}

const std::vector<float>& defaultDistanceBands() {
  static const std::vector<float> edges = {0, 10, 20, 30, 40};
  return edges;
}

void DepthErrors::add(const KittiLabel& label, float z_m, float nearest_z_m, float nearest_z_sigma_m) {
  if (!labelDepthComparable(label)) return;
  const float truth = labelNearestDepth(label);
  z.add(truth, z_m);
  nearest.add(truth, nearest_z_m, nearest_z_sigma_m);
}

std::string DepthErrors::format() const {
  return "depth of kept true positives vs the label's nearest depth: z_m (median stixel)\n" +
         formatDistanceBands(z.bands(defaultDistanceBands())) + "nearest_z_m (nearest part)\n" +
         formatDistanceBands(nearest.bands(defaultDistanceBands())) +
         formatDistanceBands(nearest.bands({0.0f}));  // every range together: "all"
}

std::string formatDistanceBands(const std::vector<DistanceErrorBand>& bands) {
  std::string out;
  char line[160];
  for (const DistanceErrorBand& b : bands) {
    char range[32];
    if (b.from_m <= 0 && !std::isfinite(b.to_m)) std::snprintf(range, sizeof range, "all    ");
    else if (std::isfinite(b.to_m)) std::snprintf(range, sizeof range, "%2.0f-%2.0f m", b.from_m, b.to_m);
    else std::snprintf(range, sizeof range, "%2.0f+ m  ", b.from_m);
    std::snprintf(line, sizeof line,
                  "  %s  n %4d  bias %+6.2f m  median |err| %5.2f m  p95 %5.2f m  median %4.1f %%\n", range,
                  b.count, b.bias_m, b.median_abs_m, b.p95_abs_m, 100.0 * b.median_rel);
    out += line;
    if (b.count_with_sigma > 0) {
      std::snprintf(line, sizeof line, "           within 1 / 2 sigma %3.0f / %3.0f %%  |err|/sigma p68 %.2f\n",
                    100.0 * b.within_1sigma, 100.0 * b.within_2sigma, b.p68_abs_over_sigma);
      out += line;
    }
  }
  return out;
}

}  // namespace nerv

#include "validator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_map>

namespace nerv::validator {
namespace {

std::string percent(float fraction) {
  return std::to_string(static_cast<int>(std::lround(fraction * 100.0f))) + "%";
}

std::string metres(float value) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.2f m", value);
  return buf;
}

bool finiteStats(const NormalStats& s) {
  return std::isfinite(s.density) && std::isfinite(s.ground_fraction) &&
         std::isfinite(s.object_fraction) && std::isfinite(s.error_fraction) &&
         s.num_normals >= 0 && s.num_samples >= 0;
}

Verdict unvalidated(int roi_id, const Params& p, std::string reason) {
  Verdict v;
  v.roi_id = roi_id;
  v.label = "unvalidated";
  v.score = 0.0f;
  v.kept = p.keep_unvalidated;
  v.reason = "unvalidated: " + std::move(reason);
  return v;
}

// Normals were measured but decide nothing (too few, or mixed): a box lower
// than min_unvalidated_height_m is then kerb, bush or lawn clutter far more
// often than an obstacle, and is removed - with the reason saying so.
Verdict undecided(const Hypothesis& h, const Params& p, std::string reason) {
  Verdict v = unvalidated(h.id, p, std::move(reason));
  if (h.height_m > 0 && h.height_m < p.min_unvalidated_height_m) {
    v.kept = false;
    v.reason += ", lower than " + metres(p.min_unvalidated_height_m);
  }
  return v;
}

Verdict rejected(int roi_id, const char* label, float score, std::string reason) {
  Verdict v;
  v.roi_id = roi_id;
  v.label = label;
  v.score = std::clamp(score, 0.0f, 1.0f);
  v.kept = false;
  v.reason = std::move(reason);
  return v;
}

}  // namespace

Params readParams(ConfigSection& s) {
  Params p;
  s.get("min_object_fraction", p.min_object_fraction, 0.0, 1.0);
  s.get("max_ground_fraction", p.max_ground_fraction, 0.0, 1.0);
  s.get("max_error_fraction", p.max_error_fraction, 0.0, 1.0);
  s.get("min_normals", p.min_normals, 1, 1000000);
  s.get("min_error_density", p.min_error_density, 0.0, 1.0);
  s.get("keep_unvalidated", p.keep_unvalidated);
  s.get("min_height_m", p.min_height_m, 0.0, 100.0);
  s.get("max_height_m", p.max_height_m, 0.0, 100.0);
  s.get("pole_max_width_m", p.pole_max_width_m, 0.0, 10.0);
  s.get("max_width_m", p.max_width_m, 0.0, 1000.0);
  s.get("max_surface_tilt_deg", p.max_surface_tilt_deg, 0.0, 90.0);
  s.get("min_surface_normals", p.min_surface_normals, 1, 1000000);
  s.get("min_ground_normals", p.min_ground_normals, 1, 1000000);
  s.get("min_unvalidated_height_m", p.min_unvalidated_height_m, 0.0, 10.0);
  s.get("max_surface_tilt_distance_m", p.max_surface_tilt_distance_m, 0.0, 1000.0);
  s.get("duplicate_min_iou", p.duplicates.min_iou, 0.0, 1.0);
  s.get("duplicate_max_row_offset_px", p.duplicates.max_row_offset_px, 0, 1000);
  s.get("duplicate_max_depth_ratio", p.duplicates.max_depth_ratio, 0.0, 1.0);
  s.get("pole_part_min_height_m", p.pole_parts.min_height_m, 0.0, 100.0);
  s.get("pole_part_max_depth_ratio", p.pole_parts.max_depth_ratio, 0.0, 1.0);
  s.get("pole_part_min_overlap", p.pole_parts.min_overlap, 0.0, 1.0);
  if (p.min_height_m >= p.max_height_m)
    throw ConfigError("config key '" + s.path() + ".min_height_m' must be below max_height_m");
  return p;
}

Verdict classify(const Hypothesis& h, const NormalStats* stats, const Params& p) {
  const int id = h.id;
  if (stats == nullptr) return unvalidated(id, p, "no normals");
  const NormalStats& s = *stats;
  if (!finiteStats(s)) return unvalidated(id, p, "invalid normal statistics");
  // Measured, and not one valid normal: as undecided as too few (rule 3), so
  // a low box (a kerb, a lawn edge) goes; only missing or invalid statistics
  // (bad input) keep a box regardless of its height.
  if (s.num_normals == 0) return undecided(h, p, "no normals");
  if (s.num_normals < p.min_normals)
    return undecided(h, p, "only " + std::to_string(s.num_normals) + " normals (< " +
                                  std::to_string(p.min_normals) + ")");

  // Metric size sanity (0 = unknown, not checked).
  if (h.height_m > 0 && h.height_m < p.min_height_m)
    return rejected(id, "error", 1.0f, "height " + metres(h.height_m) + " below " + metres(p.min_height_m));
  const bool pole = h.width_m > 0 && h.width_m < p.pole_max_width_m;
  if (h.height_m > p.max_height_m && !pole)
    return rejected(id, "error", 1.0f, "height " + metres(h.height_m) + " above " + metres(p.max_height_m));
  if (h.width_m > p.max_width_m)
    return rejected(id, "error", 1.0f, "width " + metres(h.width_m) + " above " + metres(p.max_width_m));

  if (s.ground_fraction > p.max_ground_fraction && s.num_normals >= p.min_ground_normals)
    return rejected(id, "ground", s.ground_fraction, "ground normals " + percent(s.ground_fraction));
  if (s.error_fraction > p.max_error_fraction && s.density >= p.min_error_density)
    return rejected(id, "error", s.error_fraction,
                    "error-like normals " + percent(s.error_fraction) +
                        ", no horizontal component (density " + percent(s.density) + ")");
  const bool near_enough = p.max_surface_tilt_distance_m <= 0 || h.distance_m <= p.max_surface_tilt_distance_m;
  if (s.object_fraction < p.min_object_fraction && s.num_normals >= p.min_surface_normals && near_enough &&
      std::isfinite(s.tilt_from_ground_deg) && s.tilt_from_ground_deg < p.max_surface_tilt_deg) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "surface tilted %.0f deg from the road, object normals %s (< %s)",
                  s.tilt_from_ground_deg, percent(s.object_fraction).c_str(), percent(p.min_object_fraction).c_str());
    return rejected(id, "ground", 1.0f - s.tilt_from_ground_deg / 90.0f, buf);
  }
  if (s.object_fraction >= p.min_object_fraction) {
    Verdict v;
    v.roi_id = id;
    v.label = "object";
    v.score = std::clamp(s.object_fraction, 0.0f, 1.0f);
    v.kept = true;
    return v;
  }
  return undecided(h, p, "mixed normals: object " + percent(s.object_fraction) + " (< " +
                                percent(p.min_object_fraction) + "), ground " +
                                percent(s.ground_fraction) + ", error-like " + percent(s.error_fraction));
}

std::vector<Verdict> validate(const std::vector<Hypothesis>& hypotheses,
                              const std::vector<NormalStats>& stats, const Params& p) {
  std::unordered_map<int, const NormalStats*> by_id;
  by_id.reserve(stats.size());
  for (const NormalStats& s : stats) by_id.emplace(s.roi_id, &s);  // first one wins on duplicates
  std::vector<Verdict> out;
  out.reserve(hypotheses.size());
  for (const Hypothesis& h : hypotheses) {
    const auto it = by_id.find(h.id);
    out.push_back(classify(h, it == by_id.end() ? nullptr : it->second, p));
  }
  if (p.duplicates.min_iou > 0 || p.pole_parts.min_height_m > 0) {
    std::vector<int> normals(hypotheses.size(), 0);
    for (size_t i = 0; i < hypotheses.size(); ++i) {
      const auto it = by_id.find(hypotheses[i].id);
      if (it != by_id.end()) normals[i] = std::max(0, it->second->num_normals);
    }
    removeDuplicates(hypotheses, normals, out, p.duplicates);
    removePoleParts(hypotheses, normals, out, p.pole_parts, p.pole_max_width_m);
  }
  return out;
}

}  // namespace nerv::validator

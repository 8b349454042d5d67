#include "miss_causes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "distance_accuracy.hpp"

namespace nerv {

MissCause missCause(const KittiLabel& label, const std::vector<EvalBox>& boxes,
                    const std::vector<float>& box_depth_m, const MissCauseParams& p) {
  const EvalBox lb = labelBox(label);
  const float z = labelNearestDepth(label);  // 0: the label has no depth; then any depth is its own
  const float tol = std::max(p.depth_tolerance_m, p.depth_tolerance_rel * std::abs(z));
  bool overlaps = false;
  float best_at_depth = -1;  // highest IoU of a box at the object's depth ...
  float best_area = 0;       // ... and that box's area
  for (size_t i = 0; i < boxes.size(); ++i) {
    const float o = iou(boxes[i], lb);
    if (!(o > 0)) continue;
    overlaps = true;
    const float d = i < box_depth_m.size() ? box_depth_m[i] : NAN;
    if ((!(z > 0) || (std::isfinite(d) && std::abs(d - z) <= tol)) && o > best_at_depth)
      best_at_depth = o, best_area = area(boxes[i]);
  }
  if (!overlaps) return MissCause::NoBox;
  if (best_at_depth < 0) return MissCause::OtherDepth;
  if (best_at_depth >= p.loose_min_iou) return MissCause::LooseBox;
  return best_area > area(lb) ? MissCause::Merged : MissCause::Partial;
}

std::string missCauseName(MissCause cause, const MissCauseParams& p) {
  char iou[32];
  std::snprintf(iou, sizeof iou, "%.2g", p.loose_min_iou);
  switch (cause) {
    case MissCause::NoBox: return "no box overlaps it";
    case MissCause::LooseBox: return std::string("loose box at its depth (IoU >= ") + iou + ")";
    case MissCause::Merged: return std::string("box at its depth, IoU < ") + iou + ", larger (merged)";
    case MissCause::Partial: return std::string("box at its depth, IoU < ") + iou + ", smaller (a part)";
    case MissCause::OtherDepth: return "only boxes at another depth";
    case MissCause::RemovedByValidator: return "found by the stixels, removed by the validator";
  }
  return "?";
}

std::string missCauseKey(MissCause cause) {
  switch (cause) {
    case MissCause::NoBox: return "no_box";
    case MissCause::OtherDepth: return "other_depth";
    case MissCause::Partial: return "part";
    case MissCause::Merged: return "merged";
    case MissCause::LooseBox: return "loose_box";
    case MissCause::RemovedByValidator: return "removed_by_validator";
  }
  return "?";
}

std::vector<std::string> MissTally::addFrame(const std::vector<KittiLabel>& labels, const EvalParams& eval,
                                             const std::vector<EvalBox>& boxes,
                                             const std::vector<float>& box_depth_m,
                                             const std::vector<DetectionMatch>& all_matches,
                                             const std::vector<DetectionMatch>& kept_matches) {
  std::vector<bool> hit_all(labels.size(), false), hit_kept(labels.size(), false);
  for (const DetectionMatch& m : all_matches)
    if (m.outcome == MatchOutcome::TruePositive && m.label >= 0 && size_t(m.label) < labels.size()) hit_all[m.label] = true;
  for (const DetectionMatch& m : kept_matches)
    if (m.outcome == MatchOutcome::TruePositive && m.label >= 0 && size_t(m.label) < labels.size()) hit_kept[m.label] = true;
  std::vector<std::string> names(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) {
    const KittiLabel& l = labels[i];
    if (!isCounted(l, eval)) continue;
    MissCause cause = MissCause::RemovedByValidator;
    if (!hit_all[i]) {
      cause = missCause(l, boxes, box_depth_m, params_);
      names[i] = missCauseName(cause, params_);
      ++all_[cause][l.type];
    }
    if (!hit_kept[i]) ++kept_[cause][l.type];
  }
  return names;
}

std::string MissTally::format() const {
  std::string out;
  for (const auto& [title, table] : {std::pair<const char*, const Table*>{"misses by cause (stixel only):", &all_},
                                     {"misses by cause (stixel + SNV):", &kept_}}) {
    if (table->empty()) continue;
    out += std::string(title) + "\n";
    for (const auto& [c, by_class] : *table) {
      int n = 0;
      std::string classes;
      for (const auto& [type, k] : by_class) n += k, classes += (classes.empty() ? "" : ", ") + type + " " + std::to_string(k);
      char line[64];
      std::snprintf(line, sizeof line, "  %5d  ", n);
      out += line + missCauseName(c, params_) + ": " + classes + "\n";
    }
  }
  return out;
}

}  // namespace nerv

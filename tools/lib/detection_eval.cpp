#include "detection_eval.hpp"

#include <algorithm>
#include <cstdio>

namespace nerv {
float area(const EvalBox& b) { return std::max(0.f, b.x2 - b.x1) * std::max(0.f, b.y2 - b.y1); }

float intersection(const EvalBox& a, const EvalBox& b) {
  const float w = std::min(a.x2, b.x2) - std::max(a.x1, b.x1);
  const float h = std::min(a.y2, b.y2) - std::max(a.y1, b.y1);
  return w > 0 && h > 0 ? w * h : 0.f;
}

EvalBox detectionBox(int x, int y, int w, int h, float score) {
  return {float(x), float(y), float(x + w), float(y + h), score};
}

EvalBox labelBox(const KittiLabel& l) { return {l.x1, l.y1, l.x2 + 1, l.y2 + 1, 0}; }

float iou(const EvalBox& a, const EvalBox& b) {
  const float inter = intersection(a, b);
  const float uni = area(a) + area(b) - inter;
  return uni > 0 ? inter / uni : 0.f;
}

bool isHidden(const KittiLabel& l) { return l.occluded >= 2 || l.truncated >= 0.5f; }

std::string setKittiDifficulty(const std::string& name, EvalParams& params) {
  struct Level { const char* name; float min_height; int max_occlusion; float max_truncation; };
  static const Level levels[] = {{"easy", 40, 0, 0.15f}, {"moderate", 25, 1, 0.3f}, {"hard", 25, 2, 0.5f}};
  for (const Level& l : levels) {
    if (name != l.name) continue;
    params.min_height_px = l.min_height;
    params.max_occlusion = l.max_occlusion;
    params.max_truncation = l.max_truncation;
    params.difficulty = l.name;
    return "";
  }
  return "unknown difficulty '" + name + "' (easy, moderate or hard)";
}

std::string difficultyText(const EvalParams& p) {
  if (p.difficulty.empty()) return "";
  char buf[160];
  std::snprintf(buf, sizeof buf, ", KITTI %s (height >= %.0f px, occluded <= %d, truncated <= %.2g)",
                p.difficulty.c_str(), p.min_height_px, p.max_occlusion, p.max_truncation);
  return buf;
}

bool isBeyondDifficulty(const KittiLabel& l, const EvalParams& params) {
  return l.occluded > params.max_occlusion || l.truncated > params.max_truncation ||
         l.y2 - l.y1 < params.min_height_px;
}

bool isCounted(const KittiLabel& l, const EvalParams& params) {
  return l.type != "DontCare" && (params.classes.empty() || params.classes.count(l.type)) &&
         !(l.z > 0 && l.z > params.max_distance_m) && !(params.visible_only && isHidden(l)) &&
         !isBeyondDifficulty(l, params);
}

bool farDetectionsIgnored(const EvalParams& params) {
  return params.limit_detections && params.max_distance_m < 1e8f;
}

std::vector<DetectionMatch> matchDetections(const std::vector<EvalBox>& detections,
                                            const std::vector<KittiLabel>& labels,
                                            const EvalParams& params) {
  std::vector<int> counted, ignored, dontcare;
  for (size_t i = 0; i < labels.size(); ++i) {
    const KittiLabel& l = labels[i];
    if (l.type == "DontCare") dontcare.push_back(static_cast<int>(i));
    else if (isCounted(l, params)) counted.push_back(static_cast<int>(i));
    else ignored.push_back(static_cast<int>(i));
  }
  std::vector<size_t> order(detections.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return detections[a].score > detections[b].score; });
  std::vector<DetectionMatch> out(detections.size());
  std::vector<bool> used(counted.size(), false);
  for (const size_t k : order) {
    const EvalBox& d = detections[k];
    int best = -1;
    float best_iou = params.min_iou;
    for (size_t i = 0; i < counted.size(); ++i) {
      const float o = iou(d, labelBox(labels[counted[i]]));
      if (!used[i] && o > best_iou) {
        best_iou = o;
        best = static_cast<int>(i);
      }
    }
    if (best >= 0) {
      used[best] = true;
      out[k] = {MatchOutcome::TruePositive, counted[best]};
      continue;
    }
    // Beyond the distance limit (the detection's own depth) and matching no
    // counted object: outside the evaluated range, like the objects there.
    bool neutral = farDetectionsIgnored(params) && d.z > 0 && d.z > params.max_distance_m;
    // Lower than the difficulty's minimum height (its last row is y2 - 1), as the devkit ignores it.
    neutral = neutral || (params.min_height_px > 0 && d.y2 - 1 - d.y1 < params.min_height_px);
    for (const int g : ignored) neutral = neutral || iou(d, labelBox(labels[g])) > params.min_iou;
    for (const int g : dontcare) {
      const EvalBox b = labelBox(labels[g]);
      neutral = neutral || (area(d) > 0 && intersection(d, b) / area(d) > params.dontcare_min_overlap);
    }
    out[k].outcome = neutral ? MatchOutcome::Ignored : MatchOutcome::FalsePositive;
  }
  return out;
}

EvalCounts countMatches(const std::vector<DetectionMatch>& matches, const std::vector<KittiLabel>& labels,
                        const EvalParams& params) {
  EvalCounts c;
  for (const KittiLabel& l : labels) c.objects += isCounted(l, params) ? 1 : 0;
  for (const DetectionMatch& m : matches) {
    if (m.outcome == MatchOutcome::TruePositive) ++c.tp;
    else if (m.outcome == MatchOutcome::FalsePositive) ++c.fp;
    else ++c.ignored;
  }
  c.fn = c.objects - c.tp;
  return c;
}

EvalCounts evaluateFrame(const std::vector<EvalBox>& detections,
                         const std::vector<KittiLabel>& labels, const EvalParams& params) {
  return countMatches(matchDetections(detections, labels, params), labels, params);
}

}  // namespace nerv

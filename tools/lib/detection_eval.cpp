#include "detection_eval.hpp"

#include <algorithm>

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

EvalCounts evaluateFrame(const std::vector<EvalBox>& detections,
                         const std::vector<KittiLabel>& labels, const EvalParams& params) {
  std::vector<EvalBox> counted, ignored, dontcare;
  for (const auto& l : labels) {
    if (l.type == "DontCare") dontcare.push_back(labelBox(l));
    else if ((!params.classes.empty() && !params.classes.count(l.type)) ||
             (l.z > 0 && l.z > params.max_distance_m))
      ignored.push_back(labelBox(l));
    else
      counted.push_back(labelBox(l));
  }
  std::vector<EvalBox> dets = detections;
  std::stable_sort(dets.begin(), dets.end(),
                   [](const EvalBox& a, const EvalBox& b) { return a.score > b.score; });

  EvalCounts c;
  c.objects = static_cast<int>(counted.size());
  std::vector<bool> matched(counted.size(), false);
  for (const auto& d : dets) {
    int best = -1;
    float best_iou = params.min_iou;
    for (size_t i = 0; i < counted.size(); ++i) {
      const float o = iou(d, counted[i]);
      if (!matched[i] && o > best_iou) {
        best_iou = o;
        best = static_cast<int>(i);
      }
    }
    if (best >= 0) {
      matched[best] = true;
      ++c.tp;
      continue;
    }
    bool neutral = false;
    for (const auto& g : ignored) neutral = neutral || iou(d, g) > params.min_iou;
    for (const auto& g : dontcare)
      neutral = neutral || (area(d) > 0 && intersection(d, g) / area(d) > params.dontcare_min_overlap);
    if (neutral) ++c.ignored;
    else ++c.fp;
  }
  for (bool m : matched) c.fn += m ? 0 : 1;
  return c;
}

}  // namespace nerv

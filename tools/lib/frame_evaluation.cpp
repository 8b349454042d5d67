#include "frame_evaluation.hpp"

namespace nerv {

FrameEvaluation evaluateDetections(const detections_t& detections, const std::vector<KittiLabel>& labels,
                                   const EvalParams& params, DepthErrors& depth, MissTally& misses) {
  std::vector<EvalBox> all, kept;
  std::vector<float> all_near;
  std::vector<const detection_t*> kept_det;
  for (const auto& d : detections.detections) {
    EvalBox b = detectionBox(d.x, d.y, d.w, d.h, d.score);
    b.z = d.z_m;
    all.push_back({b.x1, b.y1, b.x2, b.y2, 0.f, b.z});  // stixel only: no scores, matched in their order
    all_near.push_back(d.nearest_z_m);
    if (d.kept) kept.push_back(b), kept_det.push_back(&d);
  }
  const auto all_matches = matchDetections(all, labels, params);
  const auto kept_matches = matchDetections(kept, labels, params);
  misses.addFrame(labels, params, all, all_near, all_matches, kept_matches);
  for (size_t k = 0; k < kept_matches.size(); ++k)
    if (kept_matches[k].outcome == MatchOutcome::TruePositive)
      depth.add(labels[kept_matches[k].label], kept_det[k]->z_m, kept_det[k]->nearest_z_m,
                kept_det[k]->nearest_z_sigma_m);
  return {countMatches(all_matches, labels, params), countMatches(kept_matches, labels, params)};
}

}  // namespace nerv

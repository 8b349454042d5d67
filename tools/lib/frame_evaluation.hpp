// One frame's DETECTIONS against its labels, as the evaluation tools score it:
// "stixel only" counts every hypothesis, "stixel + SNV" only the kept ones;
// the kept true positives' depths go into the run's depth errors and every
// counted miss into its miss tally. Shared by nerv_eval_detections and
// nerv_report, so both score a log the same way.
#pragma once

#include <vector>

#include "detection_eval.hpp"
#include "distance_accuracy.hpp"
#include "kitti_labels.hpp"
#include "miss_causes.hpp"
#include "nerv/detections_t.hpp"

namespace nerv {

struct FrameEvaluation {
  EvalCounts all, kept;
};

FrameEvaluation evaluateDetections(const detections_t& detections, const std::vector<KittiLabel>& labels,
                                   const EvalParams& params, DepthErrors& depth, MissTally& misses);

}  // namespace nerv

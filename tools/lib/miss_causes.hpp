// Why a labelled object was missed: what the boxes near it look like. Recall
// alone does not say whether an object had no box at all (the matcher lost it,
// or the stixel stage dropped it), a box at its depth that fits it loosely
// (IoU 0.3-0.5: an edge, a top, a foot off), a box at its depth far larger
// than it (merged with a neighbour at its depth) or far smaller (only a part
// of it: a sign's post without its plate, a cut), or only boxes at another
// depth (it was read as the background behind it or as an occluder in front). The false positives' counterpart is bench_detection's
// "false positives by location".
#pragma once

#include <map>
#include <string>
#include <vector>

#include "detection_eval.hpp"
#include "kitti_labels.hpp"

namespace nerv {

// In table order, from no trace of the object to a box the validator removed.
enum class MissCause {
  NoBox,              // no box overlaps the object
  OtherDepth,         // every box overlapping it lies at another depth
  Partial,            // boxes at its depth overlap it, the best with IoU < loose_min_iou, not larger than it
  Merged,             // ... the best larger than it
  LooseBox,           // the best box at its depth has IoU >= loose_min_iou (but not the match threshold)
  RemovedByValidator, // (tallies of the kept boxes only) a box the validator removed had found it
};

struct MissCauseParams {
  float loose_min_iou = 0.3f;
  float depth_tolerance_m = 1.5f;     // a box is at the object's depth within this ...
  float depth_tolerance_rel = 0.15f;  // ... or this share of the object's depth, whichever is larger
};

// label: a missed object; boxes: the frame's detections with their depths
// (box_depth_m[i] for boxes[i], the depth of the box's nearest part [m]). The
// object's depth is labelNearestDepth (its nearest corner; the labelled depth
// when it has no 3D size); a label without any depth is judged by IoU alone.
MissCause missCause(const KittiLabel& label, const std::vector<EvalBox>& boxes,
                    const std::vector<float>& box_depth_m, const MissCauseParams& params = {});

// A short phrase for tables: "no box overlaps it", "loose box at its depth (IoU >= 0.3)", ...
std::string missCauseName(MissCause cause, const MissCauseParams& params = {});
// A stable identifier for JSON: "no_box", "other_depth", "part", "merged", "loose_box",
// "removed_by_validator".
std::string missCauseKey(MissCause cause);

// The misses of an evaluation by cause and class, for "stixel only" (every box)
// and "stixel + SNV" (the kept boxes; an object only the removed boxes found is
// "found by the stixels, removed by the validator").
class MissTally {
 public:
  using Table = std::map<MissCause, std::map<std::string, int>>;  // cause -> class -> count

  explicit MissTally(MissCauseParams params = {}) : params_(params) {}
  // One frame: every box with its nearest depth, and the matches of all boxes and
  // of the kept ones (matchDetections of the same labels and eval params).
  // Returns each label's cause as a stixel-only miss, by name ("" when it was found or is
  // not counted).
  std::vector<std::string> addFrame(const std::vector<KittiLabel>& labels, const EvalParams& eval,
                                    const std::vector<EvalBox>& boxes, const std::vector<float>& box_depth_m,
                                    const std::vector<DetectionMatch>& all_matches,
                                    const std::vector<DetectionMatch>& kept_matches);
  const Table& stixelOnly() const { return all_; }
  const Table& stixelSnv() const { return kept_; }
  // Both tables as text: one line per cause, its count and the count per class.
  std::string format() const;
  const MissCauseParams& params() const { return params_; }

 private:
  MissCauseParams params_;
  Table all_, kept_;
};

}  // namespace nerv

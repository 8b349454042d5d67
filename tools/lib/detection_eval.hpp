// PASCAL-style evaluation of 2D detections against KITTI labels, as in the
// NERV reference's table: a detection is a true positive when its IoU with an
// unmatched labelled object exceeds the threshold (0.5). A second detection of
// the same object is a false positive. Detections lying mostly inside a
// DontCare region, or matching an object that is ignored (class not counted,
// or farther than max_distance_m), count neither way; ignored objects are not
// misses. The distance limit cuts both sides, as the KITTI devkit's minimum
// height does: a detection farther than max_distance_m (its own depth) that
// matches no counted object counts neither way either.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "kitti_labels.hpp"

namespace nerv {

struct EvalBox {
  float x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  float score = 0;
  float z = 0;  // the detection's depth [m] (its z_m); 0 = unknown
};

struct EvalParams {
  float min_iou = 0.5f;
  float dontcare_min_overlap = 0.5f;  // share of the detection's area inside a DontCare box
  float max_distance_m = 1e9f;        // labelled objects farther than this are ignored (z field) ...
  bool limit_detections = true;       // ... and so are unmatched detections whose z is farther
  std::set<std::string> classes;      // counted types; empty = every type but DontCare
  bool visible_only = false;          // objects largely hidden (occluded 2) or half outside the image
                                      // (truncated >= 0.5) are ignored, as by `--visible`
  // A KITTI devkit difficulty (setKittiDifficulty, `--difficulty`): objects more occluded, more
  // truncated or lower than these are ignored, and so are unmatched detections lower than
  // min_height_px. Heights as the devkit measures them: y2 - y1 with y2 the box's last row.
  int max_occlusion = 99;             // label `occluded` field (0 visible .. 3 unknown); 99 = no limit
  float max_truncation = 99.0f;       // label `truncated` field (0 .. 1); 99 = no limit
  float min_height_px = 0.0f;         // 0 = no limit
  std::string difficulty;             // the name set by setKittiDifficulty, for headers; empty = none
};

// The KITTI object benchmark's difficulties (devkit evaluate_object.cpp):
// easy: height >= 40 px, fully visible (occluded 0), truncated <= 0.15;
// moderate: >= 25 px, occluded <= 1, truncated <= 0.3;
// hard: >= 25 px, occluded <= 2, truncated <= 0.5.
// Returns an error naming the problem for any other name (params unchanged).
std::string setKittiDifficulty(const std::string& name, EvalParams& params);

struct EvalCounts {
  int objects = 0, tp = 0, fp = 0, fn = 0, ignored = 0;
  void add(const EvalCounts& o) {
    objects += o.objects; tp += o.tp; fp += o.fp; fn += o.fn; ignored += o.ignored;
  }
  double precision() const { return tp + fp > 0 ? double(tp) / (tp + fp) : 0; }
  double recall() const { return tp + fn > 0 ? double(tp) / (tp + fn) : 0; }
  double f1() const {
    const double p = precision(), r = recall();
    return p + r > 0 ? 2 * p * r / (p + r) : 0;
  }
};

float area(const EvalBox& b);
float intersection(const EvalBox& a, const EvalBox& b);
float iou(const EvalBox& a, const EvalBox& b);

// Both sides of the box convention. A detection box x, y, w, h (hypotheses,
// DETECTIONS) covers columns [x, x + w) and rows [y, y + h). KITTI label
// boxes (and the synthetic ones, tight boxes of the pixels seeing the
// object) give the first and last pixel columns and rows, both included, so
// a label's right and bottom move out by one pixel: a detection covering
// exactly the labelled pixels has IoU 1 (PASCAL VOC counts pixels alike).
EvalBox detectionBox(int x, int y, int w, int h, float score = 0);
EvalBox labelBox(const KittiLabel& label);

// A labelled object the count includes: not DontCare, its class counted, not
// farther than max_distance_m, and visible when visible_only. The others are
// neither hits nor misses, and detections on them count neither way.
bool isCounted(const KittiLabel& label, const EvalParams& params);
// Whether unmatched detections beyond the distance limit count neither way:
// a limit is set and limit_detections is on (what the tools' headers report).
bool farDetectionsIgnored(const EvalParams& params);
// Largely hidden or half outside the image (what visible_only ignores).
bool isHidden(const KittiLabel& label);
// ", KITTI moderate (height >= 25 px, occluded <= 1, truncated <= 0.3)" for the tools'
// headers, or "" when no difficulty is set.
std::string difficultyText(const EvalParams& params);
// Outside the difficulty of params: more occluded, more truncated or lower than its limits.
bool isBeyondDifficulty(const KittiLabel& label, const EvalParams& params);

// What became of each detection of a frame: a true positive of label `label`
// (an index into the labels), a false positive, or ignored (DontCare, or an
// ignored object). Same order as the detections.
enum class MatchOutcome { TruePositive, FalsePositive, Ignored };
struct DetectionMatch {
  MatchOutcome outcome = MatchOutcome::FalsePositive;
  int label = -1;
};
std::vector<DetectionMatch> matchDetections(const std::vector<EvalBox>& detections,
                                            const std::vector<KittiLabel>& labels,
                                            const EvalParams& params);

// The counts of one frame's matches (matchDetections of the same labels and params).
EvalCounts countMatches(const std::vector<DetectionMatch>& matches, const std::vector<KittiLabel>& labels,
                        const EvalParams& params);

// One frame: detections (any order; matched by descending score) vs labels.
EvalCounts evaluateFrame(const std::vector<EvalBox>& detections,
                         const std::vector<KittiLabel>& labels, const EvalParams& params);

}  // namespace nerv

// Second boxes on one object. The stixel stage can make two hypotheses of
// the same stixels (a post's tower and the group it stood in, two layers of
// one strip), and both are validated as objects. Two kept boxes are one
// object only when they agree on everything a box says: the same rows (top
// and bottom within max_row_offset_px), the same depth (within
// max_depth_ratio) and IoU above min_iou. A looser test (IoU or containment
// alone) also merged different road users at one depth - a cyclist before a
// car, a pedestrian at a post, two parked cars (docs/validator.md); those
// differ in depth or rows.
#pragma once

#include <vector>

#include "perception_types.hpp"

namespace nerv::validator {

struct DuplicateParams {
  float min_iou = 0.5f;            // 0 = off
  int max_row_offset_px = 3;       // tops and bottoms this close
  float max_depth_ratio = 0.05f;   // depths this close, relative to the nearer
};

// IoU of two boxes (x, y, w, h; columns [x, x + w)).
float boxIou(const Box& a, const Box& b);

// verdicts[i] belongs to hypotheses[i]; normals[i] is its number of normals.
// Of each duplicate pair of kept hypotheses the one with fewer normals (then
// the smaller box, then the later one) is removed, reason "duplicate of
// hypothesis N (IoU 0.71, same rows and depth)". Returns how many were removed.
int removeDuplicates(const std::vector<Hypothesis>& hypotheses, const std::vector<int>& normals,
                     std::vector<Verdict>& verdicts, const DuplicateParams& params);

}  // namespace nerv::validator

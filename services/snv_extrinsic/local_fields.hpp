// The integral fields of the local SNV (NERV slides 20-21): one over the rows the
// ground samples need (all columns), and one per ROI that does not lie inside
// those rows, over the ROI and its margin (IntegralNormalField::prepare with a
// region). Every grid pixel gets the normal a whole-image field would give it,
// while boxes that reach up into the sky no longer make the ground field cover
// the whole frame (docs/snv.md "Speed").
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "integral_normals.hpp"

namespace nerv::snv {

class LocalFields {
 public:
  // rois: clipped to the image by the caller; ground_rows may be empty (no ground).
  void prepare(const cv::Mat& disparity, const StereoCamera& cam, const IntegralNormalParams& params,
               cv::Range ground_rows, const std::vector<cv::Rect>& rois);

  const IntegralNormalField& ground() const { return ground_; }
  // The field to read ROI i of the last prepare() from.
  const IntegralNormalField& roi(size_t i) const { return which_[i] < 0 ? ground_ : own_[which_[i]]; }
  // ROIs of the last prepare() with a field of their own.
  int ownFields() const { return used_; }

 private:
  // Kept across frames: prepare() reuses their buffers (a fresh field
  // page-faulted its ~3 MB every frame).
  IntegralNormalField ground_;
  std::vector<IntegralNormalField> own_;
  std::vector<int> which_;  // -1: the ground field, else an index into own_
  int used_ = 0;
};

}  // namespace nerv::snv

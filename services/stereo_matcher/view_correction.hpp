// The right view put back where the calibration expects it. A rig knocked or re-mounted
// since its calibration moves the right view's rows (rectification_check.hpp measures how: a
// plane dy = a + b (x - W/2) + c (y - H/2) of the right view's rows minus the left's), and
// the matcher, which searches along rows, loses a third of the detections' F1 at half a row
// (KITTI 0926); a camera turned about its vertical axis adds a constant e to every disparity
// (disparity_offset.hpp), which moves every distance (a pixel: 8-10 % at 30-40 m). Until the
// rig is recalibrated the stereo_matcher resamples each right view before matching,
//
//   out(x, y) = right(x - b v, y + a + b u + c v),   u = x - W/2, v = y - H/2
//
// the offset a and the vertical scale c as rows only, the turn b as the rotation about the
// view's centre that it is (a camera turned by b radians about its axis moves a point b u
// down and b v left), bilinear, the border replicated; and takes e off every disparity it
// matched (the same as moving the right view's content e to the right, without resampling
// it: on KITTI 0926 the resampled view's blur cost 0.02-0.04 of F1 that this does not).
// Nothing to correct leaves the view and the disparity as they are, byte for byte. When to
// correct and by how much is rig_check.hpp's.
#pragma once

#include <opencv2/core.hpp>

#include "row_plane.hpp"

namespace nerv::stereo {

class ViewCorrection {
 public:
  // The rows the right views are corrected by from now on (zero: none).
  void setRows(const RowPlane& plane);
  // The disparity offset taken off every disparity from now on [px] (0: none).
  void setColumns(double offset_px);
  const RowPlane& rows() const { return plane_; }
  double columns() const { return columns_px_; }
  // right: an 8-bit gray view. Returns it as it is while no correction is set, else the
  // corrected view (valid until the next call). The maps are built once per correction and size.
  const cv::Mat& apply(const cv::Mat& right);
  // disparity: the matcher's CV_32F result (<= 0 invalid), corrected in place: e taken off every
  // valid disparity; one left at 0 or below by it is invalid (beyond the horizon).
  void correctDisparity(cv::Mat& disparity) const;

 private:
  RowPlane plane_;
  double columns_px_ = 0;
  cv::Size size_;
  cv::Mat map_xy_, map_frac_, out_;
};

}  // namespace nerv::stereo

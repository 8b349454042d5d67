// Rows put back where the calibration expects them. A rig knocked or re-mounted since its
// calibration moves the right view's rows (rectification_check.hpp measures how: a plane
// dy = a + b (x - W/2) + c (y - H/2) of the right view's rows minus the left's), and the
// matcher, which searches along rows, loses a third of the detections' F1 at half a row
// (KITTI 0926). Until the rig is recalibrated the stereo_matcher resamples each right view
// by the measured plane before matching:
//
//   out(x, y) = right(x - b v, y + a + b u + c v),   u = x - W/2, v = y - H/2
//
// the offset a and the vertical scale c as rows only, the turn b as the rotation about the
// view's centre that it is (a camera turned by b radians about its axis moves a point b u
// down and b v left), bilinear, the border replicated. A zero plane leaves the view as it
// is, byte for byte. When to correct and by how much is rig_check.hpp's.
#pragma once

#include <opencv2/core.hpp>

#include "row_plane.hpp"

namespace nerv::stereo {

class RowCorrection {
 public:
  // The plane the right views are corrected by from now on (zero: none).
  void set(const RowPlane& plane);
  const RowPlane& plane() const { return plane_; }
  bool active() const { return !plane_.zero(); }
  // right: an 8-bit gray view. Returns it as it is while no correction is set, else the
  // corrected view (valid until the next call). The maps are built once per plane and size.
  const cv::Mat& apply(const cv::Mat& right);

 private:
  RowPlane plane_;
  cv::Size size_;
  cv::Mat map_xy_, map_frac_, out_;
};

}  // namespace nerv::stereo

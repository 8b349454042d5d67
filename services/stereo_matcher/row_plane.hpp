// The rows of a stereo rig's right view against its left's, as a plane over the view:
// dy = a + b (x - W/2) + c (y - H/2), +1 = the right view's content one row lower. What the
// row check measures (rectification_check.hpp) and what the correction undoes
// (view_correction.hpp).
#pragma once

#include <opencv2/core.hpp>

#include <cmath>

namespace nerv::stereo {

struct RowPlane {
  double offset_px = 0;  // a: the right view's rows minus the left's at the view's centre [px]
  double slope_x = 0;    // b: per column [px/px], the turn in radians
  double slope_y = 0;    // c: per row [px/px]
  bool zero() const { return offset_px == 0 && slope_x == 0 && slope_y == 0; }
  // The largest |dy| over a view of this size (at one of its corners) [px].
  double largestOver(cv::Size size) const {
    return std::abs(offset_px) + std::abs(slope_x) * 0.5 * size.width + std::abs(slope_y) * 0.5 * size.height;
  }
  RowPlane operator+(const RowPlane& o) const {
    return {offset_px + o.offset_px, slope_x + o.slope_x, slope_y + o.slope_y};
  }
  RowPlane scaled(double k) const { return {offset_px * k, slope_x * k, slope_y * k}; }
};

}  // namespace nerv::stereo

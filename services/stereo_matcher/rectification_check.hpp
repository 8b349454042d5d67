// Is the rig still rectified? In a rectified pair a scene point lies on the same row in
// both views, and the matcher searches along rows only. A rig that was knocked, warped by
// heat or re-mounted puts the right view's rows off by a fraction of a pixel or more, and
// its calibration file does not know: the disparity degrades without any other sign
// (KITTI 0926 with the right views one row down: stixel + SNV F1 0.919 -> 0.447;
// docs/stereo.md "Is the rig still rectified?").
//
// measureRowOffset: at the most textured points of a grid over the left view (the
// smaller eigenvalue of the gradients' structure tensor over the window: texture in both
// directions, so the row can be measured) that have a disparity d, Lucas-Kanade
// from (x, y) in the left view to the right view, started at (x - d, y); points whose
// horizontal result strays from the disparity, or whose track failed, are left out. Each
// point's vertical displacement (its row in the right view minus its row in the left; +1:
// the right view's content one row lower) is fitted robustly (Huber, iteratively
// reweighted) with a plane over the view, dy = a + b (x - W/2) + c (y - H/2): a camera
// pitched against the other moves every row alike (a), one turned about its optical axis
// moves the rows by an amount that grows across the view (b; 0.1 deg turns the rows of a
// 1242 px view by 1.1 px at its edges while their median stays near 0), a different
// vertical scale grows down the view (c). What the matcher suffers is the plane's |dy|
// where it matches: the 90th percentile of |a + b u + c v| over the tracked points (the
// view's corners are often sky or hood, where nothing is matched anyway).
//
// RowOffsetMonitor: the verdict over the last checks, so that one frame of glare or
// motion blur does not raise it.
#pragma once

#include <opencv2/core.hpp>

#include <string>

#include "row_plane.hpp"
#include "verdict_window.hpp"

namespace nerv::stereo {

struct RowOffsetParams {
  int grid_px = 12;               // candidate points every grid_px columns and rows
  int max_points = 200;           // the most textured candidates tracked
  int window_px = 11;             // texture and Lucas-Kanade window (square, odd)
  float max_horizontal_miss_px = 1.0f;  // |x_right - (x - d)| above this: not the matched point
  int min_points = 30;            // fewer tracked points: no measurement
};

struct RowOffset {
  bool valid = false;     // at least min_points points tracked
  int points = 0;         // points that passed
  float offset_px = 0;    // the plane at the view's centre (a), right minus left [px]
  float slope_x = 0;      // b: change per column [px/px] (about the turn in radians)
  float slope_y = 0;      // c: change per row [px/px]
  float worst_px = 0;     // 90th percentile of the plane's |dy| at the tracked points [px]
  float spread_px = 0;    // 1.4826 x median absolute deviation of the points from the plane [px]
  // What the matcher still sees of it: with a correction applied to the right view
  // (view_correction.hpp) the plane above is the rig's, the correction plus what is left of
  // it in the corrected view, and this is the 90th percentile of what is left [px]; without
  // one, the same as worst_px.
  float residual_worst_px = 0;
  RowPlane plane() const { return {offset_px, slope_x, slope_y}; }
};

// left, right: the rectified 8-bit gray views the matcher saw; disparity: its CV_32F
// result (0 = invalid); applied: the correction the right view was resampled with, added to
// what is measured in it so that the plane is the rig's against its calibration. Throws
// nothing; a flat or disparity-less frame gives valid = false.
RowOffset measureRowOffset(const cv::Mat& left, const cv::Mat& right, const cv::Mat& disparity,
                           const RowOffsetParams& params = {}, const RowPlane& applied = {});

// The median of the last `window` valid measurements (each of a, b, c, the worst and the
// residual worst), and whether the worst exceeds the limit.
class RowOffsetMonitor {
 public:
  RowOffsetMonitor(int window, float max_offset_px) : checks_(window), max_(max_offset_px) {}
  // Adds a measurement (invalid ones are ignored) and returns true when a verdict is due:
  // every `window` valid measurements.
  bool add(const RowOffset& m);
  // Forgets the remembered measurements: the next verdict is of the `window` that follow.
  void restart() { checks_.restart(); }
  int samples() const { return checks_.size(); }
  RowOffset median() const;  // each field the median of the remembered measurements
  bool misaligned() const { return samples() > 0 && median().worst_px > max_; }
  // One line: "the right view's rows lie 0.82 px below the left's at its centre and up to
  // 0.95 px off where it matches (turned 0.01 deg; median of the last 10 checks, 143-201
  // points each)".
  std::string describe() const;

 private:
  VerdictWindow<RowOffset> checks_;
  float max_;
};

}  // namespace nerv::stereo

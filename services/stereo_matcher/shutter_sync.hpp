// Were the two views taken at the same moment? Cameras whose shutters are not triggered
// together (no common trigger line, a driver that drops a trigger and catches up, two USB
// cameras) deliver pairs whose right view is a few milliseconds older or newer than the left.
// Standing still that costs nothing; driving, the right camera has moved on by speed x delay,
// and every disparity off the image centre is off in proportion: the matcher compares the
// scene from two positions along the road, not across the baseline.
//
// Moving forward by s along the optical axis moves a point at depth Z = f B / d, seen at
// (u, v) from the principal point, by v s / Z = (s / (f B)) v d rows: vertical flow that grows
// with the row's distance from the horizon and with the disparity. Between two frames of the
// left camera the forward step is the vehicle's; between the left and right views of one pair
// it is the part of the step made during the delay. Both are measured at the same textured
// points of the left view, as the coefficient k of v d in a robust fit of the vertical
// displacement:
//   left -> earlier left view:  dy = wx (f + v^2 / f) + wy u v / f + wz u + h d + k_motion v d
//     (the rotation between the frames: pitch wx, yaw wy, roll wz; h: a vertical step);
//   left -> right view:         dy = a + b u + c v + h d + k_stereo v d
//     (the rectification's plane, as in rectification_check.hpp, and a vertical baseline part).
// The right view's delay as a share of the time between the two left views is then
// -k_stereo / k_motion (the earlier view sees the scene from farther back: k_motion < 0).
// Nothing else in a calibrated rig makes a v d term: a right camera mounted ahead of the left
// would, but then the delay read stays the same at every speed, and a delay scales with it.
#pragma once

#include <opencv2/core.hpp>

#include <cmath>
#include <string>

#include "verdict_window.hpp"

namespace nerv::stereo {

struct ShutterSyncParams {
  int grid_px = 12;                     // candidates every grid_px columns and rows
  int max_points = 300;                 // the most textured candidates tracked
  int window_px = 11;                   // texture and Lucas-Kanade window (square, odd)
  float max_horizontal_miss_px = 1.0f;  // left -> right: |x_right - (x - d)| above this is not the matched point
  float max_track_error = 12.0f;        // Lucas-Kanade's mean absolute gray difference above this: lost
  int min_points = 60;                  // fewer points tracked into both views: no measurement
  // The forward step between the two left views must move the rows by at least this much at
  // the points (the 90th percentile of |k_motion v d|): standing or creeping, there is nothing
  // to compare a delay with.
  float min_motion_px = 1.5f;
};

struct ShutterSync {
  bool valid = false;       // enough points, and moving enough to measure
  bool moving = false;      // the forward step moved the rows by min_motion_px or more
  int points = 0;           // points tracked into both views
  double k_stereo = 0;      // left -> right: vertical px per (v d) [1/px^2]
  double k_motion = 0;      // left -> earlier left
  float motion_px = 0;      // 90th percentile of |k_motion v d| at the points [px]
  float offset = 0;         // the right view's delay / the time between the two left views (+: later)
};

// previous_left, left, right: 8-bit gray views (the earlier left frame, and the pair the
// matcher saw); disparity: its CV_32F result (0 = invalid); (cx, cy): the principal point and
// fx: the focal length [px] of the rectified views. Throws nothing: bad inputs, a flat frame or
// a standing vehicle give valid = false.
ShutterSync measureShutterSync(const cv::Mat& previous_left, const cv::Mat& left, const cv::Mat& right,
                               const cv::Mat& disparity, double fx, double cx, double cy,
                               const ShutterSyncParams& params = {});

// The median of the last `window` delays [ms], and whether it exceeds the limit either way.
class ViewDelayMonitor {
 public:
  ViewDelayMonitor(int window, float max_delay_ms) : delays_(window), max_(max_delay_ms) {}
  // Adds a delay [ms] (non-finite ones are ignored) and returns true when a verdict is due:
  // every `window` delays.
  bool add(float delay_ms);
  int samples() const { return delays_.size(); }
  float median() const;
  bool unsynchronised() const { return samples() > 0 && std::abs(median()) > max_; }
  // One line: "the right view is taken 4.8 ms after the left (median of the last 10 checks
  // while moving, -0.3 to 9.1 ms)".
  std::string describe() const;

 private:
  VerdictWindow<float> delays_;
  float max_;
};

}  // namespace nerv::stereo

// Were the two views taken at the same moment? Cameras whose shutters are not triggered
// together (no common trigger line, a driver that drops a trigger and catches up, two USB
// cameras) deliver pairs whose right view is a few milliseconds older or newer than the left.
// Standing still that costs nothing; driving, the right camera has moved on by speed x delay,
// and every disparity off the image centre is off in proportion: the matcher compares the
// scene from two positions along the road, not across the baseline.
//
// Moving forward by s along the optical axis moves a point at depth Z = f B / d, seen at
// (u, v) from the principal point, by about v s / Z = (s / (f B)) v d rows: vertical flow that
// grows with the row's distance from the horizon and with the disparity. Between two frames of
// the left camera the forward step is the vehicle's; between the left and right views of one
// pair it is the part of the step made during the delay. Both are measured at the same
// textured points of the left view, as the coefficient k of v d in a robust fit of the
// vertical displacement:
//   earlier left view -> left:  v - v' = wx (f + v'^2 / f) + wy u' v' / f + wz u' + h d
//                                        + k_motion v' (d - e)
//     in the earlier view's coordinates (u', v'), where the step's part is exact; the rotation
//     between the frames: pitch wx, yaw wy, roll wz; h: a vertical step; e: a disparity offset
//     (disparity_offset.hpp), a term of its own so that it does not bend k_motion;
//   left -> right view:         dy = a + b u + c v + h d + k_stereo v d
//     (the rectification's plane, as in rectification_check.hpp, and a vertical baseline part).
// The right view's delay as a share of the time between the two left views is then
// k_stereo / k_motion (k_motion > 0 driving forward).
// Nothing else in a calibrated rig makes a v d term: a right camera mounted ahead of the left
// would, but then the delay read stays the same at every speed, and a delay scales with it.
#pragma once

#include <opencv2/core.hpp>

#include <string>

#include "motion_tracks.hpp"
#include "verdict_window.hpp"

namespace nerv::stereo {

struct ShutterSyncParams {
  MotionTrackParams tracking;           // the points, their window, and when a track is lost (also left -> right)
  float max_horizontal_miss_px = 1.0f;  // left -> right: |x_right - (x - d)| above this is not the matched point
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
  double k_motion = 0;      // earlier left -> left: the forward step / (f B) [1/px^2]
  float motion_px = 0;      // 90th percentile of |k_motion v d| at the points [px]
  float offset = 0;         // the right view's delay / the time between the two left views (+: later)
};

// tracks: trackMotion() of the earlier left view, the left view and its disparity; left,
// right: the 8-bit gray pair the matcher saw; (cx, cy): the principal point and fx: the focal
// length [px] of the rectified views. Throws nothing: bad inputs, a flat frame or a standing
// vehicle give valid = false.
ShutterSync measureShutterSync(const MotionTracks& tracks, const cv::Mat& left, const cv::Mat& right, double fx,
                               double cx, double cy, const ShutterSyncParams& params = {});
// The same, tracking the points itself (params.tracking).
ShutterSync measureShutterSync(const cv::Mat& previous_left, const cv::Mat& left, const cv::Mat& right,
                               const cv::Mat& disparity, double fx, double cx, double cy,
                               const ShutterSyncParams& params = {});

// One line of a verdict over delays [ms]: "the right view is taken 4.8 ms after the left
// (median of the last 10 checks while moving, -0.3 to 9.1 ms)".
std::string describeViewDelay(const MedianVerdict& delays);

}  // namespace nerv::stereo

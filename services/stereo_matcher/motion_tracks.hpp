// The textured points of the left view that have a disparity (textured_points.hpp), followed
// back into the previous frame's left view: what the vehicle's own motion did to them. The
// rig checks that use the motion as a reference (shutter_sync.hpp, disparity_offset.hpp)
// share one tracking.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "robust_fit.hpp"
#include "textured_points.hpp"

namespace nerv::stereo {

struct MotionTrackParams {
  int grid_px = 12;              // candidates every grid_px columns and rows
  int max_points = 300;          // the most textured candidates tracked
  int window_px = 11;            // texture and Lucas-Kanade window (square, odd)
  float max_track_error = 12.0f; // Lucas-Kanade's mean absolute gray difference above this: lost
};

struct MotionTracks {
  MatchedPoints matched;            // in the left view, with where the disparity puts them in the right
  std::vector<cv::Point2f> before;  // the same points in the previous left view
  std::vector<uchar> tracked;       // 1: `before` holds a good track
};

// previous_left, left: 8-bit gray views of the same size; disparity: the left view's CV_32F
// disparity (0 = invalid). Anything else gives no points.
MotionTracks trackMotion(const cv::Mat& previous_left, const cv::Mat& left, const cv::Mat& disparity,
                         const MotionTrackParams& params = {});

// The terms of a point's image motion along one axis from the previous frame to this one, in
// the previous view's coordinates from the principal point: `along` is its coordinate on that
// axis (u' for the columns, v' for the rows), `across` the other one, d its disparity. In order:
// the rotation about the other axis (fx + along^2 / fx), the cross term of the rotation about
// this axis (along across / fx), the roll (across), a step across the axis (d), the forward step
// (along d, exact in these coordinates) and the part of it a disparity offset takes (along). One
// model for both axes: the shutter check fits the rows, the offset check the columns, and their
// coefficient 4 is the forward step / (f B), 5 minus the offset times it.
inline FitRow<6> stepFlowRow(double along, double across, double d, double fx) {
  return {fx + along * along / fx, along * across / fx, across, d, along * d, along};
}

// How far the forward step moved the points, for deciding whether there was motion enough to
// measure: |k| times the 90th percentile of `magnitudes` (|v' d| or |u' d| per point) [px].
float stepAtPoints(double k, std::vector<double> magnitudes);

}  // namespace nerv::stereo

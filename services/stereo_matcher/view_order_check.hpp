// Are the two views the right way round? A rig whose cables, drivers or topics are crossed
// delivers the right camera's image as the left one. Every scene point then lies to the
// right in the "right" view instead of to the left, the matcher (which searches positive
// disparities) finds almost nothing, and the stages behind it only say "no ground" (KITTI
// 0926 swapped: 0 hypotheses, no ground on 11 of 11 frames; docs/stereo.md "Are the views
// the right way round?").
//
// measureViewOrder: the most textured grid points of the left view are followed into the
// right view by pyramidal Lucas-Kanade from where they are (no disparity needed), and back;
// a track that does not return within half a pixel, drifts off its row, or moves less than
// a pixel sideways (far away, or lost) does not vote. In a rig the right way round the
// others move left (x_right < x_left); swapped, they move right.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

struct ViewOrderParams {
  int grid_px = 12;
  int max_points = 200;
  int window_px = 15;              // Lucas-Kanade window; with the levels the pyramid has, tracks reach ~50 px sideways
  int pyramid_levels = 4;
  float max_return_px = 0.5f;      // forward-backward: the track must come back this close
  float max_row_drift_px = 2.0f;   // |y_right - y_left| above this: not a stereo match
  float min_sideways_px = 1.0f;    // tracks moving less do not vote
  int min_votes = 30;              // fewer voting tracks: no measurement
  float swapped_share = 0.7f;      // at least this share moving right: swapped
};

struct ViewOrder {
  bool valid = false;       // at least min_votes tracks voted
  int votes = 0;
  float share_rightward = 0;  // of the votes, the share whose point lies right of its left-view position
  bool swapped = false;     // valid and share_rightward >= swapped_share
};

// left, right: 8-bit gray views of the same size; anything else gives valid = false.
ViewOrder measureViewOrder(const cv::Mat& left, const cv::Mat& right, const ViewOrderParams& params = {});

}  // namespace nerv::stereo

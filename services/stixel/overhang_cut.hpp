// Overhangs end the objects below them. A pedestrian under a tree on the
// sidewalk stands at the crown's depth: the height segmentation of its strips
// runs on up through the crown (and the trunk between), its stixels become
// taller than any road user, and the box is the tree's. The crown is wider
// than what stands below it and has no ground contact of its own: beside the
// group's strips, at the group's depth, its pixels fill the rows above the
// pedestrian but not the rows below. A row is an overhang when, on the left or
// the right of the group, at least min_fill of the strips within min_reach_m
// hold pixels at the group's depth; the group's stixels are cut below the
// lowest run of such rows that starts at least min_height_m over the road. A
// sign plate on its post reaches 0.25 m beside it (less than min_reach_m) and
// stays in the post's box. Groups narrower than min_width_m are left alone:
// a post or a bare trunk below a crown is no road user, and cut below the
// crown it would look like one.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct OverhangParams {
  float min_reach_m = 0.0f;        // an overhang reaches this far beside the group [m]; 0 = off
  float min_fill = 0.6f;           // share of the strips within that reach it fills
  float min_height_m = 1.4f;       // rows lower than this over the road are never cut
  float min_width_m = 0.0f;        // narrower groups (posts, trunks) are never cut [m] ...
  float max_width_m = 1e9f;        // ... and wider ones (facades, vehicles) neither
  float max_distance_m = 1e9f;     // farther groups are never cut: there one disparity step is metres
                                   // of depth and "the group's depth" takes in what stands behind it
  float depth_tolerance_m = 1.0f;  // a pixel is at the group's depth within this (>= 1 px)
  float ground_tolerance_m = 0.15f;// pixels this close to the road are road
  int min_rows = 3;                // consecutive overhang rows that confirm one
  int column_width_px = 5;
};

// group: the stixels of one group, left to right; their top rows are lowered
// below an overhang found beside them. Returns the first row kept (the new
// top bound), or -1 when nothing was cut.
int cutOverhang(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                std::vector<Stixel*>& group, const OverhangParams& p);

}  // namespace nerv::stixel

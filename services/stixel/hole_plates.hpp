// Sign plates the matcher left as a hole. A flat sign plate (the back of a
// sign, or a plain one) has no texture inside, and its only vertical edges
// are occlusion boundaries, so no census window on it matches at its
// disparity: the plate is an invalid hole in the disparity map, bounded by the
// background's valid pixels, directly above the post that carries it (urban
// seed 14 frame 10: a sign at 16 m, post u 380-390 found up to row 117, the
// plate's rows 80-116 invalid over u 368-390, the facade beside and above it
// valid). sign_plates.hpp and post_sides.hpp need plate pixels at the post's
// depth and find nothing there; the post's box stays the post (IoU 0.2-0.3
// with the sign's label). Here a post-like box (at most max_width_m wide, its
// top at least min_top_m over the road) is raised over the rows above it
// whose columns are a hole - at least min_hole_share of the box's columns
// invalid or at the post's depth - when those rows
//  - start at the box's top (one row bridged) and span min_plate_height_m to
//    max_plate_height_m (the plate, and the upper post where the matcher lost
//    it too);
//  - end below two rows of valid pixels at another depth, or at the image's
//    top row (a near sign's plate cut by the image): a closed hole. Above a
//    post against the sky or a blank wall the hole runs on beyond
//    max_plate_height_m and nothing is changed;
//  - are bounded on both sides within max_plate_width_m in at least half of
//    them: the box's sides widen to the hole's median extent.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "box_refinement.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct HolePlateParams {
  float max_width_m = 0.0f;          // boxes at most this wide (posts; 0 = off) ...
  float min_top_m = 1.5f;            // ... whose top stands at least this high over the road
  float min_plate_height_m = 0.15f;  // the hole spans at least this many rows [m] ...
  float max_plate_height_m = 2.0f;   // ... and at most this many (a longer run is sky or a wall)
  float max_plate_width_m = 1.2f;    // its rows are bounded within this width [m] (a plate and the matcher's band beside it)
  float min_hole_share = 0.7f;       // a hole row: this share of the box's columns invalid or at its depth
  float depth_tolerance_m = 1.0f;    // a pixel is at the post's depth within this (>= 1 px)
};

// group: the stixels of one hypothesis; box: its refined box (columns
// [x0, x1), rows [y0, y1]), raised and widened in place. Returns the number
// of rows it rose (0 when the rule does not apply).
int raiseToHolePlate(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                     const std::vector<const Stixel*>& group, const HolePlateParams& p, PixelBox& box);

}  // namespace nerv::stixel

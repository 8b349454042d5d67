// Box sides of posts across matcher holes. A sign post's box is its plate's
// width, but the plate often has no stixel of its own (no ground contact under
// it) and the box refinement (box_refinement.hpp) widens a box to it only from
// the strip edge outwards and over columns whose run of pixels at the post's
// depth is unbroken. The matcher leaves holes there: invalid pixels along the
// post's edges (left-right check) and inside an untextured plate, so a post
// narrower than its strip kept the post's width (urban: sign posts at 8-16 m,
// IoU 0.2-0.38 with the plate's label). For groups no wider than max_width_m,
// each side is scanned outwards from the refined edge: a column belongs to the
// post when it holds min_run_m of pixels at the post's disparity with no valid
// pixel at another depth between them (invalid pixels neither count nor break
// the run), and up to max_gap_m of columns that fail may lie between the post
// and such a column.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "box_refinement.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct PostSidesParams {
  float max_width_m = 0.0f;        // groups at most this wide (posts; 0 = off) ...
  float min_height_m = 1.5f;       // ... and at least this tall have their sides re-scanned
  float min_run_m = 0.4f;          // a column needs this many metres of pixels at the post's depth, holes bridged
  float max_extension_m = 0.5f;    // sides move at most this far outwards [m]
  float max_gap_m = 0.1f;          // failing columns that may lie between the post and a plate column [m]
  float depth_tolerance_m = 1.0f;  // a pixel is at the post's depth within this (>= 1 px)
  float ground_tolerance_m = 0.15f;// pixels this close to the road are road
};

// group: the stixels of one hypothesis, left to right; box: its refined box
// (columns [x0, x1), rows [y0, y1]), widened in place. Returns true when a
// side moved.
bool widenPostSides(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                    const std::vector<const Stixel*>& group, const PostSidesParams& p, PixelBox& box);

}  // namespace nerv::stixel

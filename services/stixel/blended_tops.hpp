// A far person's head read as a blend. The matcher's census window (9x7) is as
// wide as a pedestrian at 30-50 m, so above the shoulders, where the body is a
// head 3-5 px wide, the window holds more background than person: those rows
// read neither the body's disparity nor the background's but a blend between
// them, with holes where the match was ambiguous (urban seed 11 frame 10,
// pedestrian at 34 m, body 10.9 px, facade 7.7 px: label top row 164, head rows
// 164-171 at 8.7-10.1 px between holes, rows above it at most 8.5). The height
// segmentation counts the blend as a mismatch and stops at the shoulders, 1.0-
// 1.4 m over the road, and the box's top lies 8-12 px under the label's. Here
// the box of a narrow group whose top stands that low is raised over the rows
// above it that keep at least two blend pixels - at least min_share of the way
// from the background beside the box to the body, and not nearer than the body
// - as long as they form a run (one empty row bridged) and no nearer surface
// covers most of a row. A whole car is wider than max_width_m, a car's
// roof (1.4-1.5 m) and a post stand higher than max_top_m, a near object's
// window is narrower than its head (min_distance_m); with nothing matched
// above the shoulders (sky, holes) there is no blend and the top stays.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "box_refinement.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct BlendedTopParams {
  float max_extension_m = 0.0f;   // the top rises by at most this much [m]; 0 = off
  float max_width_m = 1.5f;       // only boxes at most this wide (a far person's box, widened by the
                                  // matcher's fattening to 0.7-1.3 m, or a parked car's rear piece) ...
  float min_top_m = 0.9f;         // ... whose top is at least this high over the road (lower clutter,
                                  // raised, would pass the validator's 0.8 m height check) ...
  float max_top_m = 1.35f;        // ... and at most this high (the shoulders) ...
  float min_distance_m = 20.0f;   // ... and at least this far (nearer, the window is narrower than a head)
  float min_share = 0.35f;        // a blend pixel lies this share of the way from the background to the body
  float depth_tolerance_m = 1.0f; // a pixel is at the body's depth within this (>= 1 px)
};

// Raises box.y0 over the blended head rows of the group's box (see above);
// returns the number of rows it rose (0 when the rule does not apply).
int raiseBlendedTop(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                    const std::vector<const Stixel*>& group, const BlendedTopParams& p, PixelBox& box);

}  // namespace nerv::stixel

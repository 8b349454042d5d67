// Box sides continued over a nearer occluder. A car parked behind another one
// is seen beside it and, farther along, only as a band of roof above the
// nearer car's top: the stixels end where the occluder begins (the roof band
// is a few rows, below the minimum obstacle height), so the box stops at the
// occluder's edge while the object's visible extent - the roof band - reaches
// on (synthetic urban and wet_road: parked cars at 25-40 m, IoU 0.33-0.49
// with the right edge short by a third of the car). Outwards from each side of
// a group at least min_width_m wide and at most max_height_m tall, a column continues the object when a
// nearer surface (at least min_depth_step_m nearer) occludes its lower part and
// the rows above that occluder's top - from search_above_m above the box's top
// - hold at least min_pixels valid pixels at the edge stixel's disparity, and
// at least min_fill of that band's valid pixels. Up to max_gap_m of failing
// columns may be bridged; the side moves at most max_extension_m.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "box_refinement.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct OccludedSideParams {
  float max_extension_m = 0.0f;    // a side moves at most this far over an occluder [m]; 0 = off
  float min_width_m = 0.5f;        // only groups at least this wide (not posts) ...
  float max_height_m = 3.5f;       // ... and at most this tall (not trees, facades)
  float min_depth_step_m = 2.0f;   // the occluder is nearer than the object's tolerance band by this (>= 1 px)
  float search_above_m = 0.2f;     // the band above the occluder starts this far above the box's top
  int min_pixels = 2;              // a column needs this many pixels at the object's disparity in the band ...
  float min_fill = 0.2f;           // ... and this share of the band's valid pixels (the rest: background)
  float max_gap_m = 0.15f;         // failing columns bridged between the side and a continuing column [m]
  float depth_tolerance_m = 1.0f;  // a pixel is at the object's depth within this (>= 1 px)
  float ground_tolerance_m = 0.15f;// pixels this close to the road are road
};

// group: the stixels of one hypothesis, left to right; box: its refined box
// (columns [x0, x1), rows [y0, y1]), widened in place but never beyond
// [min_x, max_x). Returns true when a side moved.
bool extendOverOccluders(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                         const std::vector<const Stixel*>& group, const OccludedSideParams& p, PixelBox& box,
                         int min_x, int max_x);

}  // namespace nerv::stixel

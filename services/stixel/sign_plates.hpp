// Sign plates over their post's foot. A thin post at 25-40 m is often lost by
// the matcher (a two-pixel column against a textured background: the
// left-right check and the background's support win), while its plate, a
// compact face of 0.4-0.8 m, and the post's foot near the road keep their
// disparity. The plate hangs above the sky cut of the free space, so the post
// leaves only a low stixel at its foot, whose height segmentation cannot reach
// over the background between foot and plate, and a lone low stixel is
// dropped (wet_road seed 7: a sign at 20-37 m covered in 0 of 30 frames).
// For each stixel at most max_foot_height_m tall, the rows above it are
// scanned in its strip for the plate: at least min_plate_height_m of rows in
// which min_row_fill of the strip's columns are at the stixel's disparity,
// starting at least min_plate_bottom_m over the road, with the columns beyond
// max_plate_width_m on both sides not at that disparity on those rows (a tree
// crown or a facade at the foot's depth is no plate). The stixel's top is
// raised to the plate's top and the stixel is returned as a post.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct SignPlateParams {
  float max_foot_height_m = 0.0f;   // stixels at most this tall are searched (0 = off)
  float min_plate_bottom_m = 1.5f;  // the plate's lowest row is at least this high over the road
  float max_plate_top_m = 5.0f;     // and its top at most this high
  float min_plate_height_m = 0.2f;  // plate rows span at least this much
  float max_plate_width_m = 1.0f;   // columns this far beside the strip must not be at its depth
  float min_row_fill = 0.4f;        // a plate row holds this share of the strip's columns at its depth
  float max_side_fill = 0.2f;       // ... and at most this share beside it
  float depth_tolerance_m = 1.0f;   // a pixel is at the stixel's depth within this (>= 1 px)
  bool nearer_beside = false;       // a pixel beside the strip nearer than the plate counts as at its depth
};

// Rows [top, bottom] of the lowest plate in columns [u, u + width) at disparity d
// (depth z_m), scanned upwards from row `lowest` to row `highest`: at least
// min_plate_height_m of rows (one missing row bridged) in which min_row_fill of the
// columns are at d and at most max_side_fill of those max_plate_width_m beside it
// on either side. top = bottom = -1 when there is none; closed when the plate
// ends below `highest` with at least min_plate_height_m of search rows above it
// whose columns [u, u + width) hold less than min_row_fill at d on average: a run
// into the search's top or the image's, or one whose strip goes on at its depth
// above it (only the sides stopped it: a crown narrowing downwards), may be part
// of a taller thing.
struct PlateRows {
  int top = -1, bottom = -1;
  bool closed = false;
  bool found() const { return top >= 0; }
};
PlateRows findPlateRows(const cv::Mat& disparity, const StereoCamera& cam, int u, int width, float d, int lowest,
                        int highest, const SignPlateParams& p);

// stixels: first-layer stixels; the tops of those under a plate are raised.
// Returns copies of the raised stixels (to be kept as posts when alone).
std::vector<Stixel> raiseToSignPlates(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
                                      std::vector<Stixel>& stixels, const SignPlateParams& p);

}  // namespace nerv::stixel

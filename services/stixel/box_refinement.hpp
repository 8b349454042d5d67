// Pixel-accurate box edges for a group of stixels. Stixels are column_width_px
// wide, so a group's union box is quantised to strips: a 0.12 m post at 20 m is
// 4 px wide but its box at least one strip, and a box edge can be off by a
// strip on either side. The left and right edges are re-cut column by column
// at the edge stixel's own disparity, and the top is lowered to the first row
// where the object (pixels at the group's depths) fills enough of the box, so
// a thin thing rising behind or above the object (a tree trunk, a facade at
// nearly the same depth) does not stretch the box. A post one or two strips
// wide fills its own columns over most of its rows, but the matcher's
// foreground fattening beside it and the road at its foot fill a quarter of
// the rows of the columns next to it, so narrow groups ask more of an edge
// column than vehicles and pedestrians, whose edge columns (wheels, legs) are
// sparse.
//
// The left edge has a second test. In a left-reference disparity map the
// background just left of a foreground object is seen by the left camera only
// (occluded in the right image); the matcher fills that band, dark and
// untextured behind a far sign, with disparities a fraction of a pixel below
// the object's, and the 1 px floor of the depth tolerance (+-4 m at 40 m) took
// them in: a sign at 40 m had its box 4-7 px too wide on the left. A surface
// that really continues leftwards at a lower disparity is a side receding from
// the camera; a side parallel to the optical axis at lateral offset X has
// d = B (u - cx) / X, so it is seen only right of the principal point, and
// between the edge stixel's centre uc and a column u left of it its disparity
// drops by d (uc - u) / (uc - cx). Below the stixel's disparity the left edge
// therefore accepts the metric tolerance, at least occluded_edge_tolerance_px,
// plus that drop, never more than the usual tolerance.
#pragma once

#include <opencv2/core.hpp>

#include <limits>
#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct BoxRefinementParams {
  float depth_tolerance_m = 1.0f;   // a pixel belongs to a stixel within this depth [m] (>= 1 px)
  float ground_tolerance_m = 0.15f; // pixels this close to the road are road, not object [m]
  float min_column_fill = 0.25f;    // an edge column needs this share of the stixel's rows ...
  float narrow_max_width_m = 0.0f;  // ... or, in a group at most this wide (a post; 0 = off) ...
  float narrow_min_column_fill = 0.4f; // ... this share (fattening and the foot fill a quarter beside a post)
  float min_column_run_m = 0.0f;    // ... or a run of this many metres of them (a sign plate on its
                                    // post; 0 = off) ...
  float max_extension_m = 0.0f;     // ... and may continue this far outside the group (at least a strip)
  float min_row_fill = 0.3f;        // the top row needs this share of the box width
  float occluded_edge_tolerance_px = 0.0f; // left edge: the floor below the edge stixel's disparity [px]
                                           // instead of 1 px, plus a receding side's drop (0 = off)
};

// Tolerance below the disparity of stixel s for column u on a box's left edge
// (see above): the metric tolerance depth_tolerance_m at s, at least band_px,
// plus the drop of a receding side between the stixel's centre and u, capped
// at max_px (the tolerance of the other edges). band_px <= 0 returns max_px.
float occludedEdgeTolerance(const Stixel& s, int u, const StereoCamera& cam, float depth_tolerance_m,
                            float band_px, float max_px);

struct PixelBox {
  int x0 = 0, x1 = 0;  // columns [x0, x1)
  int y0 = 0, y1 = 0;  // rows [y0, y1]
};

// group: the stixels of one hypothesis, left to right. `box` holds their union
// on input and the refined box on output (never wider than the union plus
// max(one strip, max_extension_m) on each side, never taller than the union).
// edge_rows_above: the edges are judged only on the stixel rows above this
// row (a post standing in a hedge: below the hedge's top the columns beside
// the post are at the post's depth too), when at least a quarter of the
// stixel's rows lie above it; default: all rows. The edges never leave
// [min_x, max_x) (a group cut beside another object at its depth).
void refineBox(const cv::Mat& disparity, const StereoCamera& cam, const GroundModel& ground,
               const std::vector<const Stixel*>& group, int column_width_px,
               const BoxRefinementParams& p, PixelBox& box,
               int edge_rows_above = std::numeric_limits<int>::max(),
               int min_x = std::numeric_limits<int>::min(), int max_x = std::numeric_limits<int>::max());

}  // namespace nerv::stixel

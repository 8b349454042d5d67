// A background gap narrower than a strip. Where a cyclist rides 0.5-1 m
// beside a parked van at about its depth (urban seeds 13 and 14, 25-36 m),
// the gap between them is 4-10 px wide: every 5 px strip straddles it, so the
// strips read the road user, the vehicle or a blend, never the background,
// and gap_strips.hpp finds no valley. The cyclist's group then takes in the
// near end of the van's receding side, and its box is 9-24 px too wide on a
// label 10-16 px wide. Column by column the gap shows: over the road user's
// rows, the median disparity of each column drops 0.5-0.9 px below the road
// user's plateau (urban 14 frame 10: 12.8 px, gap 11.9-12.4 px over 9
// columns, then the van's side rising 12.9-13.8 px; the rendered truth: 13.2,
// the background 11.15). A road user's end of the group (the same size,
// height and flatness tests as gap_strips.hpp) is cut off at the first run of
// columns beside it whose medians are farther than it by min_dip_px (and
// gap_strips' min_dip_m), at most max_gap_m wide, after which the group
// either ends or rises again by min_rise_px (a valley, not a side receding
// from the camera). The gap's columns belong to neither part.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "gap_strips.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct GapColumnParams {
  float min_dip_px = 0.0f;   // the gap's column medians lie this much farther than the end (0 = off) ...
  float min_rise_px = 0.4f;  // ... and the far side rises this much above the gap's deepest column
  int max_inside_px = 2;     // ... starting at most this many columns inside the end's strips
  int far_side_px = 10;      // ... within this many columns after the gap (two strips), and is not the end's surface
  float min_height_step_m = 0.2f;   // ... the far side is no flat continuation of the end: off its depth, a ramp, or this much taller or lower
  float min_background_m = 2.0f;     // ... and a quarter of some gap column's pixels lie this far behind the end
  float ground_tolerance_m = 0.15f;  // pixels this close to the road are road
  GapStripParams ends;       // the road user's end and the gap's width: as for gap strips
};

// group: the stixels of one group, left to right (per strip the nearest
// counts). Columns [lo, hi) of the gap as in GapCut; found = false: no cut.
GapCut findGapColumns(const std::vector<const Stixel*>& group, const cv::Mat& disparity, const StereoCamera& cam,
                      const GroundModel& ground, const GapColumnParams& p);

}  // namespace nerv::stixel

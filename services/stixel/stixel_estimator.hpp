// Disparity -> ground model (v-disparity), cleanup, stixels and obstacle
// hypotheses. The "stixel only" detector of the NERV reference (slides 3, 10).
// No transport here: services/stixel/main.cpp wires it to LCM.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "config.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct Params {
  int column_width_px = 5;               // stixel width [px]
  float max_height_above_ground_m = 2.5f;// pixels higher than this above the road are "sky"
  float ground_tolerance_m = 0.15f;      // pixels closer than this to the road plane are road
  float min_obstacle_height_m = 0.25f;   // shorter stixels are dropped
  float max_distance_m = 60.0f;          // hypotheses farther away are dropped
  float min_camera_height_m = 0.5f;      // ground lines implying another height are rejected
  float max_camera_height_m = 4.0f;
  float max_pitch_deg = 10.0f;           // ground lines implying a steeper pitch are rejected
  float group_depth_gap_m = 1.5f;        // neighbouring stixels farther apart in depth split a box
  float group_lateral_gap_m = 0.6f;      // neighbouring stixels farther apart sideways split a box
  int side_max_stixels = 3;              // a vehicle's receding side of this many strips at most ...
  float side_max_depth_m = 6.0f;         // ... ending at most this far [m] (a car's length and depth noise) ...
  float side_length_per_height = 3.0f;   // ... or this many times its height (trucks, buses) behind that group's nearest stixel ...
  float side_top_tolerance = 0.15f;      // ... continuing its top edge joins that group; 0 strips = off
  float tower_min_height_m = 0.8f;       // posts in hedges: stixels this tall (0 = off) ...
  float tower_height_ratio = 2.0f;       // ... this many times their group's median height ...
  float tower_max_width_m = 0.8f;        // ... no wider than this become hypotheses of their own
  float structure_min_height_m = 4.5f;   // stixels this tall (trees, facades: no road user is) never share a box with lower ones; 0 = off
  bool split_chains = true;              // cut a group too deep for one vehicle where a receding surface meets a face at its far end
  float hedge_post_min_ratio = 1.3f;     // a run of strips at most hedge_post_max_width_m wide whose stixels are this many times as tall as the strips beside it (0 = off) ...
  float hedge_post_min_height_m = 0.8f;  // ... each at least this tall ...
  float hedge_post_min_step_m = 0.2f;    // ... with its top this much above theirs leaves its group as a post (hedge_posts.hpp)
  float hedge_post_max_width_m = 0.45f;  // ... (the run's width) ...
  float hedge_post_max_distance_m = 30.0f; // ... at most this far
  bool hedge_post_at_group_end = true;   // ... also at a group's end, when the rest of the group lies on its far side from the image centre column
  bool tower_edges_above_surround = true;// such a post's box edges are cut on its rows above the hedge only
  bool occluded_stixels = true;          // second-layer stixels: objects seen above a nearer one (occluded_stixels.hpp)
  bool occluded_nearest = true;          // ... the nearest surface above the occluder that fills min_obstacle_height_m, not the fullest
  float sign_plate_max_foot_height_m = 1.2f; // sign plates over a post's foot (sign_plates.hpp): stixels at most this tall (0 = off) ...
  float sign_plate_min_bottom_m = 1.5f;  // ... under a plate starting at least this high over the road ...
  float sign_plate_min_height_m = 0.2f;  // ... at least this tall ...
  float sign_plate_max_width_m = 1.0f;   // ... with nothing at its depth this far beside the strip ...
  float sign_plate_min_row_fill = 0.4f;  // ... whose rows hold this share of the strip at the stixel's depth: raised to it, kept alone
  float occluded_plate_max_top_m = 5.0f; // sign plates above an occluder up to this high over the road give its strip a post stixel (occluded_plates.hpp; the sign_plate_* test); 0 = off
  float occluded_plate_max_distance_m = 40.0f; // ... at most this far ...
  float occluded_plate_max_occluder_m = 2.5f; // ... above an occluder whose top is at most this high over the road ...
  float occluded_plate_min_gap_m = 6.0f; // ... and this much nearer than the strip's second-layer stixel
  int min_stixels_per_hypothesis = 2;    // smaller groups are dropped
  bool use_extrinsics_prior = true;      // fall back to the latest EXTRINSICS when the fit is weak
  float max_disparity_px = 256.0f;       // disparities at or above are treated as invalid
  float vd_inlier_tolerance_px = 1.5f;   // v-disparity cells this close to the ground line are inliers
  int min_ground_rows = 20;              // fewer image rows supporting the ground line = weak fit
  float min_ground_disparity_span_px = 5.0f;  // ground inliers must span this disparity range
  float freespace_smoothness_m = 0.05f;  // free-space DP cost per disparity bin of boundary jump
  int freespace_jump_cap_bins = 4;       // larger boundary jumps cost no more (object edges)
  float max_clearance_m = 1.5f;          // free space: evidence not reaching this low over the road hangs over it (tree crowns); 0 = off
  float object_depth_tolerance_m = 1.5f; // height segmentation: pixels within this depth of a stixel belong to it
  float max_stixel_height_m = 10.0f;     // height segmentation looks no higher over the road (poles, trucks)
  float min_single_stixel_height_m = 0.0f; // a lone stixel at least this tall is kept as a hypothesis; 0 = never (measured: more FPs than posts found)
  float height_step_min_m = 0.25f;       // a group's end at most height_step_max_width_m wide standing this much above the rest is cut off (height_steps.hpp); 0 = off
  float height_step_max_width_m = 1.0f;  // ... (a cyclist or pedestrian beside a car at its depth) ...
  float height_step_min_height_m = 1.5f; // ... when its median stixel is at least this tall ...
  float height_step_max_height_m = 2.2f; // ... and at most this tall ...
  int height_step_min_rest_stixels = 2;  // ... and the rest keeps this many strips ...
  float height_step_min_rest_width_m = 0.7f; // ... and this width (a vehicle, not a pedestrian's shoulder), in groups ...
  float height_step_max_distance_m = 1e9f; // ... at most this far
  float depth_step_min_m = 1.0f;         // or an end whose two neighbours are this much nearer or farther (0 = off) ...
  float depth_step_min_px = 0.8f;        // ... and this many px ...
  float depth_step_max_spread_px = 0.5f; // ... flat within this [px] ...
  float depth_step_min_height_m = 1.5f;  // ... and at least this tall
  float person_pair_min_step_px = 0.8f;  // a group of two person-sized parts is cut at a disparity step this large (person_pairs.hpp); 0 = off ...
  float person_pair_min_step_m = 0.3f;   // ... and this deep [m] ...
  float person_pair_min_width_m = 0.3f;  // ... parts at least this wide ...
  float person_pair_max_width_m = 1.0f;  // ... and at most this wide ...
  float person_pair_min_height_m = 1.4f; // ... at least this tall ...
  float person_pair_max_height_m = 2.2f; // ... and at most this tall ...
  float person_pair_max_spread_px = 0.5f; // ... each flat within this [px]
  float overhang_min_reach_m = 0.8f;     // tops cut below an overhang reaching this far beside the group (tree crowns; overhang_cut.hpp); 0 = off
  float overhang_min_fill = 0.6f;        // ... filling this share of the strips within that reach ...
  float overhang_min_height_m = 1.4f;    // ... starting at least this high over the road, in groups ...
  float overhang_min_width_m = 0.45f;    // ... at least this wide (posts and bare trunks stay whole) ...
  float overhang_max_width_m = 1.2f;     // ... and at most this wide (facades and vehicles stay whole) ...
  float overhang_max_distance_m = 40.0f; // ... and at most this far
  bool refine_boxes = true;              // cut box edges at pixel level (box_refinement.hpp)
  float refine_depth_tolerance_m = 1.0f; // refinement: pixels within this depth of the edge stixel are object
  float refine_min_column_fill = 0.25f;  // refinement: an edge column needs this share of the stixel's rows
  float refine_narrow_max_width_m = 0.35f;  // refinement: ... in groups at most this wide (posts; 0 = off) ...
  float refine_narrow_min_column_fill = 0.4f; // ... this share
  float refine_min_column_run_m = 0.4f;  // refinement: ... or a run this long [m] (sign plates); 0 = off
  float refine_max_extension_m = 0.5f;   // refinement: edges may move this far outside the group (>= a strip)
  float refine_min_row_fill = 0.3f;      // refinement: the top row needs this share of the box width
  float post_sides_max_width_m = 0.5f;   // post sides across matcher holes (post_sides.hpp): groups at most this wide (0 = off) ...
  float post_sides_min_height_m = 1.5f;  // ... and at least this tall ...
  float post_sides_min_run_m = 0.4f;     // ... widen over columns holding this many metres at their depth, holes bridged ...
  float post_sides_max_extension_m = 0.5f; // ... at most this far outwards ...
  float post_sides_max_gap_m = 0.1f;     // ... across at most this much of failing columns
};

// Reads the `stixel:` section of a pipeline config into Params (ConfigError on bad keys).
Params readParams(ConfigSection& section);

// Camera pose from snv_extrinsic used when the v-disparity fit is weak.
struct GroundPrior {
  bool valid = false;
  float pitch_deg = 0, roll_deg = 0, height_m = 0;
};

struct StixelResult {
  GroundModel ground;
  std::vector<Stixel> stixels;
  std::vector<Hypothesis> hypotheses;
};

// disparity: CV_32F, left view, <= 0 or non-finite = invalid; cam must match its size.
StixelResult estimateStixels(const cv::Mat& disparity, const StereoCamera& cam,
                             const Params& params, const GroundPrior& prior = {});

}  // namespace nerv::stixel

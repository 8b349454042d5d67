// Obstacle hypotheses (ROIs): runs of neighbouring stixels at a similar depth.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "blended_tops.hpp"
#include "box_refinement.hpp"
#include "gap_columns.hpp"
#include "gap_strips.hpp"
#include "hedge_posts.hpp"
#include "height_steps.hpp"
#include "layered_tops.hpp"
#include "low_runs.hpp"
#include "nearer_fronts.hpp"
#include "person_pairs.hpp"
#include "occluded_sides.hpp"
#include "overhang_cut.hpp"
#include "hole_plates.hpp"
#include "post_sides.hpp"
#include "roof_pieces.hpp"
#include "side_slivers.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::stixel {

struct GroupingParams {
  float group_depth_gap_m = 1.5f;      // neighbours farther apart in depth split a group
  float group_lateral_gap_m = 0.6f;    // neighbours farther apart sideways split a group
  int min_stixels_per_hypothesis = 2;  // smaller groups are dropped
  int side_max_stixels = 3;            // a vehicle's receding side (this many strips at most) ...
  float side_max_depth_m = 6.0f;       // ... ending at most this far [m] (a car's length and depth noise) ...
  float side_length_per_height = 3.0f; // ... or this many times its height (trucks, buses) behind the group's nearest stixel ...
  float side_top_tolerance = 0.15f;    // ... with its top within this share of the group's height joins it; 0 strips = off
  float tower_min_height_m = 0.0f;     // a post in a hedge / on a kerb: stixels this tall ... (0 = off)
  float tower_height_ratio = 2.0f;     // ... and this many times the group's median height ...
  float tower_max_width_m = 0.8f;      // ... over at most this width leave the group as their own
  bool tower_companions = true;        // lower stixels in a tower's strips do not break its run (they group apart)
  HedgePostParams hedge_posts;         // a post half of a short hedge group leaves it as a tower (hedge_posts.hpp)
  float structure_min_height_m = 0.0f; // stixels this tall (trees, facades) and lower ones never share a group; 0 = off
  bool split_chains = true;            // a group too deep for one vehicle is cut where a receding run meets a face at its far end ...
  int chain_long_run_stixels = 8;      // ... judged over this many strips before the face when four do not decide (0 = four only)
  float chain_reversal_min_jump_px = 1.0f;  // ... or where a receding run drops to a flat face this much nearer [px] (0 = off) ...
  float chain_face_min_height_ratio = 1.5f; // ... or meets a flat face this many times as tall as its end (0 = off) ...
  float chain_face_min_height_m = 1.2f;     // ... and at least this tall [m] ...
  float chain_face_max_spread_px = 1.0f;    // ... flat: the face's four strips' disparities within this [px]
  bool tower_edges_above_surround = true;  // such a post's box edges are cut on its rows above the hedge only
  float min_obstacle_height_m = 0.25f; // lower groups are dropped
  float max_distance_m = 60.0f;        // farther groups are dropped
  float depth_sigma_px = 0.35f;        // 1-sigma disparity error of the nearest part [px]
  float min_single_stixel_height_m = 0.0f;  // a lone stixel this tall is a hypothesis; 0 = never
  HeightStepParams height_steps;       // a road user beside a lower vehicle at its depth leaves its group (height_steps.hpp)
  GapStripParams gap_strips;           // a road user cut off at the background gap beside it (gap_strips.hpp)
  GapColumnParams gap_columns;         // ... or at a gap narrower than a strip, column by column (gap_columns.hpp)
  PersonPairParams person_pairs;       // two pedestrians side by side are cut at the step between them (person_pairs.hpp)
  SideSliverParams side_slivers;       // a narrow piece of a vehicle's receding side folds into it (side_slivers.hpp)
  RoofPieceParams roof_pieces;         // a small piece stacked on a vehicle's roof line, inside its box, is dropped (roof_pieces.hpp)
  NearerFrontParams nearer_fronts;     // a lower road user in front of a taller one in the group gets its own box (nearer_fronts.hpp)
  LowRunParams low_runs;               // a low structure receding along the road gives no hypothesis (low_runs.hpp)
  OverhangParams overhang;             // stixel tops cut below an overhang beside the group (overhang_cut.hpp)
  LayerTopParams layer_tops;           // tops that ran up a surface just behind a wide group are lowered (layered_tops.hpp)
  BlendedTopParams blended_top;        // a narrow far box raised over its head read as a blend (blended_tops.hpp)
  bool refine_boxes = true;            // pixel-accurate box edges (box_refinement.hpp)
  BoxRefinementParams refinement;
  PostSidesParams post_sides;          // sides of posts widened across matcher holes (post_sides.hpp)
  HolePlateParams hole_plates;         // a post's box raised over the hole of its plate (hole_plates.hpp)
  OccludedSideParams occluded_sides;  // box sides continued over a nearer occluder (occluded_sides.hpp)
  int column_width_px = 5;             // stixel strip width (refinement looks one strip outside)
};

// The disparity and road a frame's stixels came from (for box refinement).
struct GroupingInput {
  const cv::Mat* disparity = nullptr;
  const GroundModel* ground = nullptr;
  const std::vector<Stixel>* posts = nullptr;  // stixels known to be posts (sign_plates.hpp): kept when alone
};

// stixels sorted by u (as extractStixels returns them). Hypotheses are numbered
// 0..n-1 from left to right.
// Without `input` (or with refine_boxes false) boxes are the union of the stixels.
std::vector<Hypothesis> groupStixels(const std::vector<Stixel>& stixels, const StereoCamera& cam,
                                     const GroupingParams& p, const GroupingInput& input = {});

}  // namespace nerv::stixel

// readParams: the `stixel:` config section, one key per Params field.
#include "stixel_estimator.hpp"

namespace nerv::stixel {

Params readParams(ConfigSection& c) {
  Params p;
  c.get("column_width_px", p.column_width_px, 1, 64);
  c.get("max_height_above_ground_m", p.max_height_above_ground_m, 0.1, 20.0);
  c.get("ground_tolerance_m", p.ground_tolerance_m, 0.0, 1.0);
  c.get("min_obstacle_height_m", p.min_obstacle_height_m, 0.0, 5.0);
  c.get("max_distance_m", p.max_distance_m, 1.0, 500.0);
  c.get("min_camera_height_m", p.min_camera_height_m, 0.1, 10.0);
  c.get("max_camera_height_m", p.max_camera_height_m, 0.1, 10.0);
  c.get("max_pitch_deg", p.max_pitch_deg, 0.0, 45.0);
  c.get("group_depth_gap_m", p.group_depth_gap_m, 0.0, 100.0);
  c.get("group_lateral_gap_m", p.group_lateral_gap_m, 0.0, 100.0);
  c.get("occluded_stixels", p.occluded_stixels);
  c.get("occluded_nearest", p.occluded_nearest);
  c.get("sign_plate_max_foot_height_m", p.sign_plate_max_foot_height_m, 0.0, 10.0);
  c.get("sign_plate_min_bottom_m", p.sign_plate_min_bottom_m, 0.0, 10.0);
  c.get("sign_plate_min_height_m", p.sign_plate_min_height_m, 0.01, 10.0);
  c.get("sign_plate_max_width_m", p.sign_plate_max_width_m, 0.0, 10.0);
  c.get("sign_plate_min_row_fill", p.sign_plate_min_row_fill, 0.01, 1.0);
  c.get("occluded_plate_max_top_m", p.occluded_plate_max_top_m, 0.0, 20.0);
  c.get("occluded_plate_max_distance_m", p.occluded_plate_max_distance_m, 0.0, 500.0);
  c.get("occluded_plate_max_occluder_m", p.occluded_plate_max_occluder_m, 0.0, 20.0);
  c.get("occluded_plate_min_gap_m", p.occluded_plate_min_gap_m, 0.0, 100.0);
  c.get("lone_post_min_height_m", p.lone_post_min_height_m, 0.0, 20.0);
  c.get("lone_post_max_distance_m", p.lone_post_max_distance_m, 0.0, 500.0);
  c.get("lone_post_min_gap_m", p.lone_post_min_gap_m, 0.0, 100.0);
  c.get("lone_post_min_step_px", p.lone_post_min_step_px, 0.0, 256.0);
  c.get("lone_post_side_strips", p.lone_post_side_strips, 1, 20);
  c.get("side_max_stixels", p.side_max_stixels, 0, 100);
  c.get("side_max_depth_m", p.side_max_depth_m, 0.0, 100.0);
  c.get("side_length_per_height", p.side_length_per_height, 0.0, 100.0);
  c.get("side_top_tolerance", p.side_top_tolerance, 0.0, 1.0);
  c.get("tower_min_height_m", p.tower_min_height_m, 0.0, 20.0);
  c.get("tower_height_ratio", p.tower_height_ratio, 1.0, 100.0);
  c.get("tower_max_width_m", p.tower_max_width_m, 0.01, 10.0);
  c.get("tower_edges_above_surround", p.tower_edges_above_surround);
  c.get("hedge_post_min_ratio", p.hedge_post_min_ratio, 0.0, 100.0);
  c.get("hedge_post_min_height_m", p.hedge_post_min_height_m, 0.0, 20.0);
  c.get("hedge_post_min_step_m", p.hedge_post_min_step_m, 0.0, 20.0);
  c.get("hedge_post_max_width_m", p.hedge_post_max_width_m, 0.01, 10.0);
  c.get("hedge_post_max_distance_m", p.hedge_post_max_distance_m, 0.0, 500.0);
  c.get("hedge_post_at_group_end", p.hedge_post_at_group_end);
  c.get("max_clearance_m", p.max_clearance_m, 0.0, 10.0);
  c.get("structure_min_height_m", p.structure_min_height_m, 0.0, 100.0);
  c.get("split_chains", p.split_chains);
  c.get("chain_long_run_stixels", p.chain_long_run_stixels, 0, 64);
  c.get("tower_companions", p.tower_companions);
  c.get("min_stixels_per_hypothesis", p.min_stixels_per_hypothesis, 1, 1000);
  c.get("use_extrinsics_prior", p.use_extrinsics_prior);
  c.get("max_disparity_px", p.max_disparity_px, 1.0, 4096.0);
  c.get("vd_inlier_tolerance_px", p.vd_inlier_tolerance_px, 0.1, 20.0);
  c.get("vd_obstacle_side_tolerance_px", p.vd_obstacle_side_tolerance_px, 0.0, 20.0);
  c.get("min_ground_rows", p.min_ground_rows, 2, 100000);
  c.get("min_ground_disparity_span_px", p.min_ground_disparity_span_px, 0.0, 1000.0);
  c.get("freespace_smoothness_m", p.freespace_smoothness_m, 0.0, 10.0);
  c.get("freespace_jump_cap_bins", p.freespace_jump_cap_bins, 1, 1000);
  c.get("object_depth_tolerance_m", p.object_depth_tolerance_m, 0.01, 100.0);
  c.get("max_stixel_height_m", p.max_stixel_height_m, 0.1, 100.0);
  c.get("top_near_miss_px", p.top_near_miss_px, 0.0, 10.0);
  c.get("top_max_extension_m", p.top_max_extension_m, 0.0, 5.0);
  c.get("top_min_resume_m", p.top_min_resume_m, 0.0, 5.0);
  c.get("min_single_stixel_height_m", p.min_single_stixel_height_m, 0.0, 100.0);
  c.get("height_step_min_m", p.height_step_min_m, 0.0, 10.0);
  c.get("height_step_max_width_m", p.height_step_max_width_m, 0.0, 10.0);
  c.get("height_step_min_height_m", p.height_step_min_height_m, 0.0, 10.0);
  c.get("height_step_max_height_m", p.height_step_max_height_m, 0.0, 10.0);
  c.get("height_step_min_rest_stixels", p.height_step_min_rest_stixels, 1, 1000);
  c.get("height_step_min_rest_width_m", p.height_step_min_rest_width_m, 0.0, 10.0);
  c.get("height_step_max_distance_m", p.height_step_max_distance_m, 0.0, 1e9);
  c.get("depth_step_min_m", p.depth_step_min_m, 0.0, 100.0);
  c.get("depth_step_min_px", p.depth_step_min_px, 0.0, 100.0);
  c.get("depth_step_max_spread_px", p.depth_step_max_spread_px, 0.0, 100.0);
  c.get("depth_step_min_height_m", p.depth_step_min_height_m, 0.0, 10.0);
  c.get("person_pair_min_step_px", p.person_pair_min_step_px, 0.0, 100.0);
  c.get("person_pair_min_step_m", p.person_pair_min_step_m, 0.0, 100.0);
  c.get("person_pair_min_width_m", p.person_pair_min_width_m, 0.0, 10.0);
  c.get("person_pair_max_width_m", p.person_pair_max_width_m, 0.0, 10.0);
  c.get("person_pair_min_height_m", p.person_pair_min_height_m, 0.0, 10.0);
  c.get("person_pair_max_height_m", p.person_pair_max_height_m, 0.0, 10.0);
  c.get("person_pair_max_spread_px", p.person_pair_max_spread_px, 0.0, 100.0);
  c.get("overhang_min_reach_m", p.overhang_min_reach_m, 0.0, 10.0);
  c.get("overhang_min_fill", p.overhang_min_fill, 0.01, 1.0);
  c.get("overhang_min_height_m", p.overhang_min_height_m, 0.0, 10.0);
  c.get("overhang_min_width_m", p.overhang_min_width_m, 0.0, 10.0);
  c.get("overhang_max_width_m", p.overhang_max_width_m, 0.0, 100.0);
  c.get("overhang_max_distance_m", p.overhang_max_distance_m, 0.0, 500.0);
  c.get("refine_boxes", p.refine_boxes);
  c.get("refine_depth_tolerance_m", p.refine_depth_tolerance_m, 0.01, 100.0);
  c.get("refine_min_column_fill", p.refine_min_column_fill, 0.0, 1.0);
  c.get("refine_narrow_max_width_m", p.refine_narrow_max_width_m, 0.0, 10.0);
  c.get("refine_narrow_min_column_fill", p.refine_narrow_min_column_fill, 0.0, 1.0);
  c.get("refine_min_row_fill", p.refine_min_row_fill, 0.0, 1.0);
  c.get("refine_occluded_edge_tolerance_px", p.refine_occluded_edge_tolerance_px, 0.0, 1.0);
  c.get("refine_min_column_run_m", p.refine_min_column_run_m, 0.0, 10.0);
  c.get("refine_max_extension_m", p.refine_max_extension_m, 0.0, 10.0);
  c.get("post_sides_max_width_m", p.post_sides_max_width_m, 0.0, 10.0);
  c.get("post_sides_min_height_m", p.post_sides_min_height_m, 0.0, 100.0);
  c.get("post_sides_min_run_m", p.post_sides_min_run_m, 0.01, 10.0);
  c.get("post_sides_max_extension_m", p.post_sides_max_extension_m, 0.0, 10.0);
  c.get("post_sides_max_gap_m", p.post_sides_max_gap_m, 0.0, 10.0);
  c.get("occluded_side_max_extension_m", p.occluded_side_max_extension_m, 0.0, 10.0);
  c.get("occluded_side_min_width_m", p.occluded_side_min_width_m, 0.0, 10.0);
  c.get("occluded_side_max_height_m", p.occluded_side_max_height_m, 0.0, 100.0);
  c.get("occluded_side_min_step_m", p.occluded_side_min_step_m, 0.0, 100.0);
  c.get("occluded_side_min_pixels", p.occluded_side_min_pixels, 1, 1000);
  c.get("occluded_side_min_fill", p.occluded_side_min_fill, 0.0, 1.0);
  if (p.min_camera_height_m >= p.max_camera_height_m)
    throw ConfigError("config key '" + c.path() + ".min_camera_height_m' must be below max_camera_height_m");
  if (p.ground_tolerance_m >= p.min_camera_height_m)
    throw ConfigError("config key '" + c.path() + ".ground_tolerance_m' must be below min_camera_height_m");
  return p;
}

}  // namespace nerv::stixel

// Composes the stixel stage: v-disparity -> ground line -> occupancy and free
// space -> stixels -> hypotheses (NERV reference slides 3, 10).
#include "stixel_estimator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "free_space.hpp"
#include "ground_geometry.hpp"
#include "ground_line_fit.hpp"
#include "hypothesis_grouping.hpp"
#include "lone_posts.hpp"
#include "obstacle_map.hpp"
#include "occluded_plates.hpp"
#include "occluded_vehicles.hpp"
#include "occluded_stixels.hpp"
#include "sign_plates.hpp"
#include "stixel_extraction.hpp"
#include "v_disparity.hpp"

namespace nerv::stixel {

namespace {

GroundModel estimateGround(const cv::Mat& disparity, const StereoCamera& cam, const Params& p,
                           const GroundPrior& prior) {
  GroundLineFitParams fp;
  fp.min_camera_height_m = p.min_camera_height_m;
  fp.max_camera_height_m = p.max_camera_height_m;
  fp.max_pitch_deg = p.max_pitch_deg;
  fp.inlier_tolerance_px = p.vd_inlier_tolerance_px;
  fp.obstacle_side_tolerance_px = p.vd_obstacle_side_tolerance_px;
  fp.min_inlier_rows = p.min_ground_rows;
  fp.min_disparity_span_px = p.min_ground_disparity_span_px;
  const VDisparity vd = computeVDisparity(disparity, p.max_disparity_px, 2);
  const GroundLine line = fitGroundLine(vd, cam, fp);
  if (line.ok) {
    GroundModel g = groundModelFromLine(line.slope, line.intercept, cam, "v_disparity");
    g.inliers = line.inlier_cells;
    g.residual_px = line.residual_px;
    return g;
  }
  // A weak fit never invents a road: the prior pose or an explicit "none".
  // The prior is checked like a fit: a pose no vehicle camera can have is ignored.
  const bool prior_usable = prior.valid && std::isfinite(prior.pitch_deg) &&
                            std::isfinite(prior.height_m) &&
                            prior.height_m >= p.min_camera_height_m &&
                            prior.height_m <= p.max_camera_height_m &&
                            std::abs(prior.pitch_deg) <= p.max_pitch_deg;
  if (p.use_extrinsics_prior && prior_usable) {
    float a = 0, b = 0;
    groundLineFromPose(prior.pitch_deg, prior.height_m, cam, a, b);
    GroundModel g = groundModelFromLine(a, b, cam, "extrinsics_prior");
    g.roll_deg = prior.roll_deg;
    return g;
  }
  return GroundModel{};
}

}  // namespace

BoxRefinementParams boxRefinementParams(const Params& params) {
  BoxRefinementParams r;
  r.depth_tolerance_m = params.refine_depth_tolerance_m;
  r.ground_tolerance_m = params.ground_tolerance_m;
  r.min_column_fill = params.refine_min_column_fill;
  r.narrow_max_width_m = params.refine_narrow_max_width_m;
  r.narrow_min_column_fill = params.refine_narrow_min_column_fill;
  r.min_row_fill = params.refine_min_row_fill;
  r.occluded_edge_tolerance_px = params.refine_occluded_edge_tolerance_px;
  r.min_column_run_m = params.refine_min_column_run_m;
  r.max_extension_m = params.refine_max_extension_m;
  return r;
}

BlendedTopParams blendedTopParams(const Params& params) {
  BlendedTopParams b;
  b.max_extension_m = params.blended_top_max_extension_m;
  b.max_width_m = params.blended_top_max_width_m;
  b.min_top_m = params.blended_top_min_top_m;
  b.max_top_m = params.blended_top_max_top_m;
  b.min_distance_m = params.blended_top_min_distance_m;
  b.min_share = params.blended_top_min_share;
  b.depth_tolerance_m = params.refine_depth_tolerance_m;
  return b;
}

OccludedVehicleParams occludedVehicleParams(const Params& params) {
  OccludedVehicleParams ov;
  ov.vehicle_width_m = params.occluded_vehicle_width_m;
  ov.min_width_m = params.occluded_vehicle_min_width_m;
  ov.max_width_m = params.occluded_vehicle_max_width_m;
  ov.min_height_m = params.occluded_vehicle_min_height_m;
  ov.max_height_m = params.occluded_vehicle_max_height_m;
  ov.min_depth_step_m = params.occluded_vehicle_min_step_m;
  ov.touch_px = params.column_width_px;
  return ov;
}

RoofPieceParams roofPieceParams(const Params& params) {
  RoofPieceParams r;
  r.max_stixels = params.roof_piece_max_stixels;
  r.min_host_width_m = params.side_sliver_min_host_width_m;
  r.min_host_height_m = params.side_sliver_min_host_height_m;
  r.max_host_height_m = params.side_sliver_max_host_height_m;
  r.max_gap_px = params.roof_piece_max_gap_px;
  r.max_depth_m = params.side_max_depth_m;
  r.top_tolerance_px = params.roof_piece_top_tolerance_px;
  return r;
}

StixelResult estimateStixels(const cv::Mat& disparity, const StereoCamera& cam,
                             const Params& params, const GroundPrior& prior) {
  if (!disparity.empty() && disparity.type() != CV_32F)
    throw std::invalid_argument("estimateStixels: disparity must be CV_32F");
  if (!disparity.empty() && (disparity.cols != cam.width || disparity.rows != cam.height))
    throw std::invalid_argument("estimateStixels: disparity size does not match the camera");
  const std::string problem = cam.problem();
  if (!problem.empty()) throw std::invalid_argument("estimateStixels: camera: " + problem);

  StixelResult result;
  if (disparity.empty()) return result;
#ifdef NERV_STIXEL_PROFILE
  auto t_prev = std::chrono::steady_clock::now();
#define STIXEL_MARK(what) { auto t_now = std::chrono::steady_clock::now(); std::fprintf(stderr, "%s %.3f ms  ", what, std::chrono::duration<double, std::milli>(t_now - t_prev).count()); t_prev = t_now; }
#else
#define STIXEL_MARK(what)
#endif
  result.ground = estimateGround(disparity, cam, params, prior);
  STIXEL_MARK("ground");
  ObservedParams observed_params;
  observed_params.column_width_px = params.column_width_px;
  observed_params.max_distance_m = params.max_distance_m;
  observed_params.min_observed = params.min_observed_share;
  if (!result.ground.valid) {
    result.observed = observeFreeSpace(disparity, cam, result.ground, {}, observed_params);  // nothing is free
    return result;
  }

  StixelExtractionParams ep;
  FreeSpaceParams& fs = ep.free_space;
  fs.column_width_px = params.column_width_px;
  fs.ground_tolerance_m = params.ground_tolerance_m;
  fs.max_height_above_ground_m = params.max_height_above_ground_m;
  fs.min_obstacle_height_m = params.min_obstacle_height_m;
  fs.max_distance_m = params.max_distance_m;
  fs.max_disparity_px = params.max_disparity_px;
  fs.smoothness_m = params.freespace_smoothness_m;
  fs.jump_cap_bins = params.freespace_jump_cap_bins;
  fs.max_clearance_m = params.max_clearance_m;
  ep.object_depth_tolerance_m = params.object_depth_tolerance_m;
  ep.max_stixel_height_m = params.max_stixel_height_m;
  ep.occluded_nearest = params.occluded_nearest;
  ep.top_near_miss_px = params.top_near_miss_px;
  ep.top_max_extension_m = params.top_max_extension_m;
  ep.top_min_resume_m = params.top_min_resume_m;

  const OccupancyGrid grid = buildOccupancy(disparity, cam, result.ground, fs);
  STIXEL_MARK("occupancy");
  const std::vector<int> boundary = solveFreeSpace(grid, fs);
  result.observed = observeFreeSpace(disparity, cam, result.ground, boundary, observed_params);
  STIXEL_MARK("free_space");
  const cv::Mat obstacle_map = obstacleDisparityMap(disparity, result.ground, fs);
  result.stixels = extractStixels(disparity, obstacle_map, cam, result.ground, boundary, ep);
  STIXEL_MARK("stixels");
  SignPlateParams sp;
  sp.max_foot_height_m = params.sign_plate_max_foot_height_m;
  sp.min_plate_bottom_m = params.sign_plate_min_bottom_m;
  sp.min_plate_height_m = params.sign_plate_min_height_m;
  sp.max_plate_width_m = params.sign_plate_max_width_m;
  sp.min_row_fill = params.sign_plate_min_row_fill;
  sp.depth_tolerance_m = params.refine_depth_tolerance_m;
  std::vector<Stixel> posts = raiseToSignPlates(disparity, cam, result.ground, result.stixels, sp);
  LonePostParams lp;
  lp.min_height_m = params.lone_post_min_height_m;
  lp.max_distance_m = params.lone_post_max_distance_m;
  lp.min_gap_m = params.lone_post_min_gap_m;
  lp.min_step_px = params.lone_post_min_step_px;
  lp.side_strips = params.lone_post_side_strips;
  const std::vector<Stixel> lone = findLonePosts(result.stixels, cam, lp);
  posts.insert(posts.end(), lone.begin(), lone.end());
  STIXEL_MARK("plates+lone");
  if (params.occluded_stixels) {
    std::vector<Stixel> behind = extractOccludedStixels(disparity, obstacle_map, cam, result.ground, result.stixels, ep);
    STIXEL_MARK("occluded");
    OccludedPlateParams op;
    op.max_plate_top_m = params.occluded_plate_max_top_m;
    op.max_distance_m = params.occluded_plate_max_distance_m;
    op.max_occluder_height_m = params.occluded_plate_max_occluder_m;
    op.min_gap_m = params.occluded_plate_min_gap_m;
    op.plate = sp;
    const std::vector<Stixel> plates = placeOccludedPlates(disparity, cam, result.ground, result.stixels, behind, ep, op);
    posts.insert(posts.end(), plates.begin(), plates.end());
    result.stixels.insert(result.stixels.end(), behind.begin(), behind.end());
    std::stable_sort(result.stixels.begin(), result.stixels.end(),
                     [](const Stixel& a, const Stixel& b) { return a.u < b.u; });
    STIXEL_MARK("occluded_plates");
  }

  GroupingParams gp;
  gp.group_depth_gap_m = params.group_depth_gap_m;
  gp.group_lateral_gap_m = params.group_lateral_gap_m;
  gp.min_stixels_per_hypothesis = params.min_stixels_per_hypothesis;
  gp.side_max_stixels = params.side_max_stixels;
  gp.side_max_depth_m = params.side_max_depth_m;
  gp.side_length_per_height = params.side_length_per_height;
  gp.side_top_tolerance = params.side_top_tolerance;
  gp.tower_min_height_m = params.tower_min_height_m;
  gp.tower_height_ratio = params.tower_height_ratio;
  gp.tower_max_width_m = params.tower_max_width_m;
  gp.tower_edges_above_surround = params.tower_edges_above_surround;
  gp.hedge_posts.min_ratio = params.hedge_post_min_ratio;
  gp.hedge_posts.min_height_m = params.hedge_post_min_height_m;
  gp.hedge_posts.min_step_m = params.hedge_post_min_step_m;
  gp.hedge_posts.max_width_m = params.hedge_post_max_width_m;
  gp.hedge_posts.max_distance_m = params.hedge_post_max_distance_m;
  gp.hedge_posts.at_group_end = params.hedge_post_at_group_end;
  gp.structure_min_height_m = params.structure_min_height_m;
  gp.split_chains = params.split_chains;
  gp.chain_long_run_stixels = params.chain_long_run_stixels;
  gp.chain_reversal_min_jump_px = params.chain_reversal_min_jump_px;
  gp.chain_face_min_height_ratio = params.chain_face_min_height_ratio;
  gp.chain_face_min_height_m = params.chain_face_min_height_m;
  gp.chain_face_max_spread_px = params.chain_face_max_spread_px;
  gp.tower_companions = params.tower_companions;
  gp.min_obstacle_height_m = params.min_obstacle_height_m;
  gp.max_distance_m = params.max_distance_m;
  gp.depth_sigma_px = params.depth_sigma_px;
  gp.min_single_stixel_height_m = params.min_single_stixel_height_m;
  gp.height_steps.min_step_m = params.height_step_min_m;
  gp.height_steps.max_width_m = params.height_step_max_width_m;
  gp.height_steps.min_height_m = params.height_step_min_height_m;
  gp.height_steps.max_height_m = params.height_step_max_height_m;
  gp.height_steps.min_rest_stixels = params.height_step_min_rest_stixels;
  gp.height_steps.min_rest_width_m = params.height_step_min_rest_width_m;
  gp.height_steps.max_distance_m = params.height_step_max_distance_m;
  gp.height_steps.min_depth_step_m = params.depth_step_min_m;
  gp.height_steps.min_depth_step_px = params.depth_step_min_px;
  gp.height_steps.max_end_spread_px = params.depth_step_max_spread_px;
  gp.height_steps.depth_step_min_height_m = params.depth_step_min_height_m;
  gp.gap_strips.min_dip_px = params.gap_strip_min_dip_px;
  gp.gap_strips.min_dip_m = params.gap_strip_min_dip_m;
  gp.gap_strips.min_end_dip_px = params.gap_strip_min_end_dip_px;
  gp.gap_strips.max_end_foot_gap_m = params.gap_strip_max_end_foot_gap_m;
  gp.gap_strips.max_gap_m = params.gap_strip_max_gap_m;
  gp.gap_strips.max_end_width_m = params.gap_strip_max_end_width_m;
  gp.gap_strips.min_height_m = params.gap_strip_min_height_m;
  gp.gap_strips.max_height_m = params.gap_strip_max_height_m;
  gp.gap_strips.max_spread_px = params.gap_strip_max_spread_px;
  gp.gap_strips.min_end_stixels = params.min_stixels_per_hypothesis;
  gp.gap_columns.min_dip_px = params.gap_column_min_dip_px;
  gp.gap_columns.min_rise_px = params.gap_column_min_rise_px;
  gp.gap_columns.min_background_m = params.gap_column_min_background_m;
  gp.gap_columns.ground_tolerance_m = params.ground_tolerance_m;
  gp.gap_columns.ends = gp.gap_strips;
  gp.person_pairs.min_step_px = params.person_pair_min_step_px;
  gp.person_pairs.min_step_m = params.person_pair_min_step_m;
  gp.person_pairs.min_width_m = params.person_pair_min_width_m;
  gp.person_pairs.max_width_m = params.person_pair_max_width_m;
  gp.person_pairs.min_height_m = params.person_pair_min_height_m;
  gp.person_pairs.max_height_m = params.person_pair_max_height_m;
  gp.person_pairs.max_spread_px = params.person_pair_max_spread_px;
  gp.person_pairs.max_blend_strips = params.person_pair_max_blend_strips;
  gp.person_pairs.min_blend_part_strips = params.person_pair_min_blend_part_strips;
  gp.side_slivers.max_stixels = params.side_sliver_max_stixels;
  gp.side_slivers.max_width_m = params.side_sliver_max_width_m;
  gp.side_slivers.min_host_width_m = params.side_sliver_min_host_width_m;
  gp.side_slivers.min_host_height_m = params.side_sliver_min_host_height_m;
  gp.side_slivers.max_host_height_m = params.side_sliver_max_host_height_m;
  gp.side_slivers.top_tolerance_m = params.side_sliver_top_tolerance_m;
  gp.side_slivers.min_fold_share = params.side_sliver_min_fold_share;
  gp.side_slivers.tall_max_gap_strips = params.side_sliver_tall_max_gap_strips;
  gp.side_slivers.tall_max_stixels = params.side_sliver_tall_max_stixels;
  gp.side_slivers.tall_max_width_m = params.side_sliver_tall_max_width_m;
  gp.side_slivers.tall_max_top_spread_m = params.side_sliver_tall_max_top_spread_m;
  gp.side_slivers.tall_host_m = params.side_sliver_tall_host_m;
  gp.side_slivers.tall_top_tolerance_m = params.side_sliver_tall_top_tolerance_m;
  gp.side_slivers.max_depth_m = params.side_max_depth_m;
  gp.side_slivers.length_per_height = params.side_length_per_height;
  gp.side_slivers.column_width_px = params.column_width_px;
  gp.roof_pieces = roofPieceParams(params);
  gp.nearer_fronts.min_step_m = params.nearer_front_min_step_m;
  gp.nearer_fronts.min_step_px = params.nearer_front_min_step_px;
  gp.nearer_fronts.max_height_m = params.nearer_front_max_height_m;
  gp.nearer_fronts.min_height_m = params.nearer_front_min_height_m;
  gp.nearer_fronts.min_rise_m = params.nearer_front_min_rise_m;
  gp.low_runs.max_height_m = params.low_run_max_height_m;
  gp.low_runs.min_depth_span_m = params.low_run_min_depth_span_m;
  gp.low_runs.min_stixels = params.low_run_min_stixels;
  gp.overhang.min_reach_m = params.overhang_min_reach_m;
  gp.overhang.min_fill = params.overhang_min_fill;
  gp.overhang.min_height_m = params.overhang_min_height_m;
  gp.overhang.min_width_m = params.overhang_min_width_m;
  gp.overhang.max_width_m = params.overhang_max_width_m;
  gp.overhang.max_distance_m = params.overhang_max_distance_m;
  gp.layer_tops.min_separation_m = params.layer_top_min_separation_m;
  gp.layer_tops.min_separation_px = params.layer_top_min_separation_px;
  gp.layer_tops.min_layer_share = params.layer_top_min_share;
  gp.layer_tops.min_width_m = params.layer_top_min_width_m;
  gp.layer_tops.ground_tolerance_m = params.ground_tolerance_m;
  gp.overhang.depth_tolerance_m = params.refine_depth_tolerance_m;
  gp.overhang.ground_tolerance_m = params.ground_tolerance_m;
  gp.overhang.column_width_px = params.column_width_px;
  gp.blended_top = blendedTopParams(params);
  gp.refine_boxes = params.refine_boxes;
  gp.column_width_px = params.column_width_px;
  gp.refinement = boxRefinementParams(params);
  gp.post_sides.max_width_m = params.post_sides_max_width_m;
  gp.post_sides.min_height_m = params.post_sides_min_height_m;
  gp.post_sides.min_run_m = params.post_sides_min_run_m;
  gp.post_sides.max_extension_m = params.post_sides_max_extension_m;
  gp.post_sides.max_gap_m = params.post_sides_max_gap_m;
  gp.post_sides.depth_tolerance_m = params.refine_depth_tolerance_m;
  gp.post_sides.ground_tolerance_m = params.ground_tolerance_m;
  gp.hole_plates.max_width_m = params.hole_plate_max_width_m;
  gp.hole_plates.min_top_m = params.hole_plate_min_top_m;
  gp.hole_plates.min_plate_height_m = params.hole_plate_min_height_m;
  gp.hole_plates.max_plate_height_m = params.hole_plate_max_height_m;
  gp.hole_plates.max_plate_width_m = params.hole_plate_max_hole_width_m;
  gp.hole_plates.min_hole_share = params.hole_plate_min_share;
  gp.hole_plates.depth_tolerance_m = params.refine_depth_tolerance_m;
  gp.occluded_sides.max_extension_m = params.occluded_side_max_extension_m;
  gp.occluded_sides.min_width_m = params.occluded_side_min_width_m;
  gp.occluded_sides.max_height_m = params.occluded_side_max_height_m;
  gp.occluded_sides.min_depth_step_m = params.occluded_side_min_step_m;
  gp.occluded_sides.min_pixels = params.occluded_side_min_pixels;
  gp.occluded_sides.min_fill = params.occluded_side_min_fill;
  gp.occluded_sides.depth_tolerance_m = params.refine_depth_tolerance_m;
  gp.occluded_sides.ground_tolerance_m = params.ground_tolerance_m;
  result.hypotheses = groupStixels(result.stixels, cam, gp, {&disparity, &result.ground, &posts});
  widenOccludedVehicles(result.hypotheses, cam, occludedVehicleParams(params));
  STIXEL_MARK("grouping");
#ifdef NERV_STIXEL_PROFILE
  std::fprintf(stderr, "\n");
#endif
  return result;
}

}  // namespace nerv::stixel

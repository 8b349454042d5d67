#include "snv_extrinsic.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "adaptive_mean_shift.hpp"
#include "camera_height.hpp"
#include "entropy.hpp"
#include "ground_plane_fit.hpp"
#include "ground_samples.hpp"
#include "integral_normals.hpp"
#include "local_normals.hpp"
#include "lowest_surface.hpp"
#include "roi_normal_stats.hpp"
#include "slope_pitch.hpp"
#include "super_snv.hpp"

namespace nerv::snv {

IntegralNormalParams normalParams(const Params& p) {
  IntegralNormalParams n;
  n.depth_change_px = p.depth_change_px;
  n.depth_change_rel = p.depth_change_rel;
  n.window_base_px = p.window_base_px;
  n.window_px_per_m = p.window_px_per_m;
  n.max_radius_px = p.max_radius_px;
  n.smooth_disparity = p.smooth_disparity;
  return n;
}

GroundSampleParams groundParams(const Params& p) {
  GroundSampleParams g;
  g.max_depth_m = p.ground_max_depth_m;
  g.min_depth_m = p.ground_min_depth_m;
  g.disparity_tol_px = p.ground_disparity_tol_px;
  g.disparity_tol_rel = p.ground_disparity_tol_rel;
  g.prior_cone_deg = p.ground_prior_cone_deg;
  g.lower_margin_px = p.ground_lower_margin_px;
  return g;
}

namespace {

PoseFilterParams filterParams(const Params& p) {
  PoseFilterParams f;
  f.pitch_process_var_deg2 = p.filter_process_var_deg2;
  f.roll_process_var_deg2 = p.filter_roll_process_var_deg2;
  f.height_process_var_m2 = p.filter_height_process_var_m2;
  f.pitch_measurement_var_deg2 = p.filter_pitch_meas_var_deg2;
  f.roll_measurement_var_deg2 = p.filter_roll_meas_var_deg2;
  f.height_measurement_var_m2 = p.filter_height_meas_var_m2;
  f.adaptive = p.filter_adaptive;
  return f;
}

RoiStatsParams roiParams(const Params& p) {
  RoiStatsParams r;
  r.ground_tolerance_deg = p.ground_tolerance_deg;
  r.upright_tolerance_deg = p.upright_tolerance_deg;
  r.facing_cone_deg = p.facing_cone_deg;
  r.upright_consistency_fraction = p.upright_consistency_fraction;
  return r;
}

// Super-SNV on one angle: histogram mode -> adaptive mean shift.
struct AngleEstimate {
  float mode = 0, mean = 0;
  MeanShiftResult shift;
};

// O(n): radix sort, then the histogram mode read off the sorted run (the
// references buildAngleHistogram and std::sort give the same values, tested).
AngleEstimate estimateAngle(std::vector<float>& values, const Params& p) {
  AngleEstimate e;
  sortAngles(values);
  e.mode = sortedModeDeg(values, p.histogram_bin_deg);
  e.mean = static_cast<float>(std::accumulate(values.begin(), values.end(), 0.0) / values.size());
  e.shift = adaptiveMeanShift(values, e.mode, p.mean_shift_fraction, p.mean_shift_stop_deg);
  return e;
}

}  // namespace

Params readParams(ConfigSection& s) {
  Params p;
  s.get("interval_px", p.interval_px, 1, 64);
  s.get("histogram_bin_deg", p.histogram_bin_deg, 0.001, 5.0);
  s.get("mean_shift_stop_deg", p.mean_shift_stop_deg, 1e-5, 1.0);
  s.get("mean_shift_fraction", p.mean_shift_fraction, 0.05, 1.0);
  s.get("ground_tolerance_deg", p.ground_tolerance_deg, 0.5, 60.0);
  s.get("filter_process_var_deg2", p.filter_process_var_deg2, 0.0, 100.0);
  s.get("depth_change_px", p.depth_change_px, 0.01, 100.0);
  s.get("depth_change_rel", p.depth_change_rel, 0.0, 1.0);
  s.get("window_base_px", p.window_base_px, 2.0, 200.0);
  s.get("window_px_per_m", p.window_px_per_m, 0.0, 10.0);
  s.get("max_radius_px", p.max_radius_px, 1, 50);
  s.get("smooth_disparity", p.smooth_disparity);
  s.get("ground_max_depth_m", p.ground_max_depth_m, 1.0, 200.0);
  s.get("ground_min_depth_m", p.ground_min_depth_m, 0.0, 50.0);
  s.get("ground_disparity_tol_px", p.ground_disparity_tol_px, 0.0, 50.0);
  s.get("ground_disparity_tol_rel", p.ground_disparity_tol_rel, 0.0, 1.0);
  s.get("ground_prior_cone_deg", p.ground_prior_cone_deg, 1.0, 60.0);
  s.get("ground_lower_margin_px", p.ground_lower_margin_px, -2000, 2000);
  s.get("min_ground_normals", p.min_ground_normals, 1, 10000000);
  s.get("plane_fit", p.plane_fit);
  s.get("plane_tukey_k", p.plane_tukey_k, 1.0, 20.0);
  s.get("plane_lowest_surface", p.plane_lowest_surface);
  s.get("lowest_surface_band_px", p.lowest_surface_band_px, 1, 1000);
  s.get("lowest_surface_min_fraction", p.lowest_surface_min_fraction, 0.0, 1.0);
  s.get("lowest_surface_tolerance", p.lowest_surface_tolerance, 0.001, 1.0);
  s.get("lowest_surface_passes", p.lowest_surface_passes, 1, 10);
  s.get("residual_entropy_bin", p.residual_entropy_bin, 1e-4, 1.0);
  s.get("pitch_source", p.pitch_source, {"mean_shift", "slope", "plane"});
  s.get("plane_pitch_inliers_only", p.plane_pitch_inliers_only);
  s.get("plane_pitch_gate_deg", p.plane_pitch_gate_deg, 0.0, 90.0);
  s.get("plane_pitch_gate_radius_share", p.plane_pitch_gate_radius_share, 0.0, 10.0);
  s.get("slope_inliers_only", p.slope_inliers_only);
  s.get("slope_mean_shift", p.slope_mean_shift);
  s.get("slope_tukey_k", p.slope_tukey_k, 1.0, 20.0);
  s.get("filter_adaptive", p.filter_adaptive);
  s.get("entropy_full_scale_bits", p.entropy_full_scale_bits, 0.1, 30.0);
  s.get("min_confidence", p.min_confidence, 0.0, 1.0);
  s.get("min_height_m", p.min_height_m, 0.0, 100.0);
  s.get("max_height_m", p.max_height_m, 0.0, 100.0);
  s.get("filter_roll_process_var_deg2", p.filter_roll_process_var_deg2, 0.0, 100.0);
  s.get("filter_height_process_var_m2", p.filter_height_process_var_m2, 0.0, 10.0);
  s.get("filter_pitch_meas_var_deg2", p.filter_pitch_meas_var_deg2, 1e-8, 100.0);
  s.get("filter_roll_meas_var_deg2", p.filter_roll_meas_var_deg2, 1e-8, 100.0);
  s.get("filter_height_meas_var_m2", p.filter_height_meas_var_m2, 1e-10, 10.0);
  s.get("upright_tolerance_deg", p.upright_tolerance_deg, 0.5, 89.0);
  s.get("facing_cone_deg", p.facing_cone_deg, 0.0, 89.0);
  s.get("upright_consistency_fraction", p.upright_consistency_fraction, 0.0, 1.0);
  if (p.min_height_m >= p.max_height_m)
    throw ConfigError("config key '" + s.path() + ".min_height_m' must be below max_height_m");
  if (p.ground_min_depth_m >= p.ground_max_depth_m)
    throw ConfigError("config key '" + s.path() +
                      ".ground_min_depth_m' must be below ground_max_depth_m");
  return p;
}

SnvExtrinsicEstimator::SnvExtrinsicEstimator(const Params& params)
    : params_(params), filter_(filterParams(params)) {
  if (params_.interval_px < 1) throw std::invalid_argument("snv: interval_px must be >= 1");
}

void SnvExtrinsicEstimator::resetFilter() { filter_ = PoseFilter(filterParams(params_)); }

SnvResult SnvExtrinsicEstimator::process(const cv::Mat& disparity, const StereoCamera& cam,
                                         const std::vector<Hypothesis>& rois,
                                         const GroundModel& ground) {
  if (disparity.type() != CV_32F)
    throw std::invalid_argument("snv: disparity must be CV_32F");
  if (const std::string why = cam.problem(); !why.empty())
    throw std::invalid_argument("snv: camera: " + why);
  if (disparity.cols != cam.width || disparity.rows != cam.height)
    throw std::invalid_argument("snv: disparity size does not match the camera");

  SnvResult res;
  res.interval_px = params_.interval_px;
  const int interval = params_.interval_px;
  const cv::Rect image(0, 0, disparity.cols, disparity.rows);
  const GroundSampleParams gp = groundParams(params_);

  // The local SNV's fields: the ground band, and each ROI outside it on its own (local_fields.hpp).
  std::vector<cv::Rect> rects;
  rects.reserve(rois.size());
  for (const Hypothesis& h : rois) rects.push_back(cv::Rect(h.box.x, h.box.y, h.box.w, h.box.h) & image);
  const cv::Range ground_rows = groundRows(cam, ground, gp);
  fields_.prepare(disparity, cam, normalParams(params_), ground_rows, rects);
  const IntegralNormalField& field = fields_.ground();

  // Super-SNV pose from the ground normals.
  filter_.predict();
  PoseEstimate& pose = res.pose;
  const std::vector<GroundSample> samples =
      selectGroundSamples(field, disparity, cam, ground, gp, ground_rows, interval);
  res.ground_samples = static_cast<int>(samples.size());
  pose.num_normals = res.ground_samples;
  pose.valid = false;
  pose.status = "no_ground";
  cv::Vec3f instant_normal(0, -1, 0);
  if (res.ground_samples >= params_.min_ground_normals) {
    std::vector<cv::Vec3f> normals(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) normals[i] = samples[i].n;
    std::vector<float> pitch(samples.size()), roll(samples.size());
    normalAnglesDeg(normals.data(), static_cast<int>(normals.size()), pitch.data(), roll.data());
    const AngleEstimate ep = estimateAngle(pitch, params_);  // sorts pitch
    const AngleEstimate er = estimateAngle(roll, params_);
    pose.pitch_mode_deg = ep.mode;
    pose.pitch_mean_deg = ep.mean;
    pose.pitch_mean_shift_deg = ep.shift.estimate;
    pose.inliers = ep.shift.inliers;
    pose.entropy = windowEntropyBits(pitch, ep.shift.estimate, params_.mean_shift_fraction,
                                     params_.histogram_bin_deg);
    pose.instant_pitch_deg = ep.shift.estimate;
    pose.instant_roll_deg = er.shift.estimate;
    instant_normal = normalFromPitchRoll(pose.instant_pitch_deg, pose.instant_roll_deg);
    std::vector<cv::Vec3f> points;
    points.reserve(samples.size());
    for (const GroundSample& s : samples) points.push_back(s.p);
    pose.instant_height_m = medianCameraHeight(points, instant_normal);
    // Samples on the road surface itself (all, unless plane_lowest_surface) and their points.
    std::vector<unsigned char> on_road(samples.size(), 1);
    std::vector<cv::Vec3f> road_points = points;
    if (params_.plane_fit) {
      // Roll from the robust road plane through the ground samples on the road
      // surface (see ground_plane_fit.hpp and the lowest-surface selection below),
      // started from the super-SNV plane. Pitch stays the
      // mean-shift value: the plane's pitch is pulled by raised sidewalks and
      // SGBM fattening at the far rows (measured 0.08-0.23 deg p95 vs 0.06-0.18
      // deg), its roll is not (0.015-0.034 deg p95 vs 0.27-0.52 deg).
      std::vector<PlanePoint> pts(samples.size());
      for (size_t i = 0; i < samples.size(); ++i)
        pts[i] = {static_cast<float>(samples[i].u), static_cast<float>(samples[i].v), samples[i].d};
      const DisparityPlane start = planeFromNormal(instant_normal, pose.instant_height_m, cam);
      PlaneFitParams fit;
      fit.tukey_k = params_.plane_tukey_k;
      DisparityPlane road_start = start;
      if (params_.plane_lowest_surface) {
        // Only the samples on the lowest surface (lowest_surface.hpp): raised
        // sidewalks parallel to the road otherwise capture the plane. The
        // selection is repeated from the plane fitted to the previous one.
        LowestSurfaceParams lp;
        lp.band_rows = params_.lowest_surface_band_px;
        lp.min_peak_fraction = params_.lowest_surface_min_fraction;
        lp.tolerance = params_.lowest_surface_tolerance;
        DisparityPlane ref = start;
        std::vector<PlanePoint> sub;
        for (int pass = 0; pass < params_.lowest_surface_passes; ++pass) {
          if (selectLowestSurface(pts, ref, cam, lp, on_road) < params_.min_ground_normals) {
            on_road.assign(samples.size(), 1);
            break;
          }
          sub.clear();
          for (size_t i = 0; i < pts.size(); ++i)
            if (on_road[i]) sub.push_back(pts[i]);
          const DisparityPlane next = fitDisparityPlane(sub, cam, fit, &ref);
          if (!next.valid) break;
          ref = next;
        }
        road_start = ref;
        road_points.clear();
        for (size_t i = 0; i < samples.size(); ++i)
          if (on_road[i]) road_points.push_back(samples[i].p);
      }
      std::vector<PlanePoint> road_pts;  // the samples on the road surface
      road_pts.reserve(pts.size());
      for (size_t i = 0; i < pts.size(); ++i)
        if (on_road[i]) road_pts.push_back(pts[i]);
      // Started from the last selection's plane (on the same samples it converges
      // at once), else from the super-SNV plane.
      const DisparityPlane plane = fitDisparityPlane(road_pts, cam, fit, &road_start);
      if (plane.valid) {
        pose.instant_roll_deg = normalRollDeg(planeNormal(plane, cam));
        instant_normal = normalFromPitchRoll(pose.instant_pitch_deg, pose.instant_roll_deg);
        pose.instant_height_m = medianCameraHeight(road_points, instant_normal);
        // Entropy of the relative residuals (d - d_plane) / d of every ground
        // sample (1 % bins = 1.65 cm of height at 1.65 m): SGBM noise fills a
        // few bins; trap pixels that pass the ground tests widen it.
        std::vector<float> res(samples.size());
        for (size_t i = 0; i < samples.size(); ++i)
          res[i] = static_cast<float>(samples[i].d - plane.disparity(cam, samples[i].u, samples[i].v)) /
                   samples[i].d;
        pose.entropy = sampleEntropyBits(res, params_.residual_entropy_bin);
      }
    }
    // The samples whose per-normal pitch lies in the final mean-shift window.
    const float win_lo = ep.shift.estimate - ep.shift.radius, win_hi = ep.shift.estimate + ep.shift.radius;
    const auto inShiftWindow = [&](const GroundSample& s) {
      const float pd = normalPitchDeg(s.n);
      return pd >= win_lo && pd <= win_hi;
    };
    if (params_.pitch_source == "slope") {
      // Instant pitch from the normalised vertical slopes (slope_pitch.hpp), whose
      // residual is linear in the disparity noise; the mean shift on the per-normal
      // pitch is biased by that pitch's skewed noise. Started from the mean shift,
      // at the roll chosen above.
      std::vector<SlopeSample> slopes;
      slopes.reserve(samples.size());
      for (const GroundSample& s : samples) {
        if (params_.slope_inliers_only && !inShiftWindow(s)) continue;
        slopes.push_back({static_cast<float>(s.u), static_cast<float>(s.v),
                          normalisedVerticalSlope(s.n, static_cast<float>(s.u), static_cast<float>(s.v), cam)});
      }
      SlopePitchParams sp;
      sp.mean_shift = params_.slope_mean_shift;
      sp.fraction = params_.mean_shift_fraction;
      sp.tukey_k = params_.slope_tukey_k;
      const SlopePitchResult fit = fitSlopePitch(slopes, cam, pose.instant_roll_deg, pose.instant_pitch_deg, sp);
      if (fit.valid) {
        pose.instant_pitch_deg = fit.pitch_deg;
        instant_normal = normalFromPitchRoll(pose.instant_pitch_deg, pose.instant_roll_deg);
        pose.instant_height_m = medianCameraHeight(points, instant_normal);
      }
    }
    if (params_.plane_fit && params_.pitch_source == "plane") {
      // Pitch from a second plane fit on the samples whose per-normal pitch lies in
      // the mean-shift window (road-like orientation; kerbs, car bodies and the
      // far rows' fattened patches mostly fall outside), started from the
      // mean-shift pitch and the plane roll. Unlike the per-normal pitch it uses
      // disparity levels over the whole road extent, not 2r-row slopes (which the
      // matchers bias low by 1-20 %, docs/snv.md). A region with biased disparity
      // can capture the plane (puddles on wet_road, nerv_sgm patches): then it
      // disagrees with the mean shift by more than the gate and the mean shift is kept.
      std::vector<PlanePoint> pts;
      pts.reserve(samples.size());
      for (size_t i = 0; i < samples.size(); ++i) {
        const GroundSample& s = samples[i];
        if ((params_.plane_pitch_inliers_only && !inShiftWindow(s)) || !on_road[i]) continue;
        pts.push_back({static_cast<float>(s.u), static_cast<float>(s.v), s.d});
      }
      const DisparityPlane start = planeFromNormal(instant_normal, pose.instant_height_m, cam);
      PlaneFitParams fit;
      fit.tukey_k = params_.plane_tukey_k;
      const DisparityPlane plane = fitDisparityPlane(pts, cam, fit, &start);
      const float plane_pitch = plane.valid ? normalPitchDeg(planeNormal(plane, cam)) : 0.0f;
      const float gate = std::max(params_.plane_pitch_gate_deg, params_.plane_pitch_gate_radius_share * ep.shift.radius);
      if (plane.valid && std::abs(plane_pitch - pose.instant_pitch_deg) <= gate) {
        pose.instant_pitch_deg = plane_pitch;
        instant_normal = normalFromPitchRoll(pose.instant_pitch_deg, pose.instant_roll_deg);
        pose.instant_height_m = medianCameraHeight(road_points, instant_normal);
      }
    }
    pose.confidence = entropyConfidence(pose.entropy, params_.entropy_full_scale_bits);

    if (pose.confidence < params_.min_confidence) {
      pose.status = "low_confidence";
    } else if (!(pose.instant_height_m >= params_.min_height_m &&
                 pose.instant_height_m <= params_.max_height_m)) {
      pose.status = "implausible_height";
    } else {
      pose.valid = true;
      pose.status = "ok";
      filter_.update(pose.instant_pitch_deg, pose.instant_roll_deg, pose.instant_height_m);
    }
  }
  if (filter_.initialised()) {
    pose.pitch_deg = filter_.pitch().value();
    pose.roll_deg = filter_.roll().value();
    pose.height_m = filter_.height().value();
    pose.filter_pitch_var = filter_.pitch().variance();
  }

  // The ground normal the ROI classes are measured against: this frame's when
  // valid, else the filtered one, else the stixel model's, else straight up.
  cv::Vec3f g(0, -1, 0);
  if (pose.valid)
    g = instant_normal;
  else if (filter_.initialised())
    g = normalFromPitchRoll(pose.pitch_deg, pose.roll_deg);
  else if (ground.valid)
    g = normalFromPitchRoll(ground.pitch_deg, ground.roll_deg);
  for (int k = 0; k < 3; ++k) res.ground_normal[k] = g[k];

  // Local SNV statistics per ROI.
  const RoiStatsParams rp = roiParams(params_);
  res.rois.reserve(rois.size());
  std::vector<LocalNormal> normals;
  for (size_t i = 0; i < rois.size(); ++i) {
    normals.clear();
    const int n_samples = localNormalsInRect(fields_.roi(i), rects[i], interval, normals);
    res.rois.push_back(computeRoiStats(rois[i].id, n_samples, normals, g, rp));
  }
  return res;
}

}  // namespace nerv::snv

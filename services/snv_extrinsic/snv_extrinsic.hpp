// Surface normal vectors from disparity, super-SNV camera pose and per-ROI
// normal statistics (NERV reference slides 11-28). No transport here.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "config.hpp"
#include "ground_samples.hpp"
#include "integral_normals.hpp"
#include "local_fields.hpp"
#include "perception_types.hpp"
#include "pose_filter.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv {

struct Params {
  int interval_px = 4;                 // sampling interval of the local normals [px]
  float histogram_bin_deg = 0.1f;      // pitch histogram bin
  float mean_shift_stop_deg = 0.01f;   // mean shift stops when it moves less than this
  float mean_shift_fraction = 0.5f;    // adaptive radius holds this fraction of the vectors
  float ground_tolerance_deg = 15.0f;  // normal within this of the ground normal = ground-like
  float filter_process_var_deg2 = 0.05f;  // temporal filter: pitch random walk per frame

  // Integral-image normals (integral_normals.hpp).
  float depth_change_px = 1.0f;      // disparity jump between neighbours that is a discontinuity [px]
  float depth_change_rel = 0.05f;    // ... or this share of the disparity, whichever is larger
  float window_base_px = 6.0f;       // depth-dependent window T = base + per_m * Z [px]
  float window_px_per_m = 0.2f;      // growth of T with depth [px/m]
  int max_radius_px = 8;             // cap of the adaptive radius r [px]
  bool smooth_disparity = true;      // box-smooth disparity (exact on planes) instead of depth

  // Ground samples (ground_samples.hpp).
  float ground_max_depth_m = 30.0f;      // farther road normals are too noisy to use [m]
  float ground_min_depth_m = 2.0f;       // nearer samples are ignored [m]
  float ground_disparity_tol_px = 1.0f;  // |d - d_ground(v)| for a ground sample [px]
  float ground_disparity_tol_rel = 0.05f;// ... or this share of d_ground(v)
  float ground_prior_cone_deg = 20.0f;   // ground normals lie within this of the camera's -y [deg]
  int ground_lower_margin_px = 10;       // without a ground model: rows below cy + this [px]
  int min_ground_normals = 50;           // fewer ground normals: no pose ("no_ground")

  // Road plane refinement (ground_plane_fit.hpp).
  bool plane_fit = true;                 // instant roll from the robust plane through the ground samples
  float plane_tukey_k = 2.5f;            // its biweight cut-off in robust sigmas of the relative residual
  bool plane_lowest_surface = true;      // planes and height only from samples on the lowest horizontal surface (lowest_surface.hpp: no sidewalks)
  int lowest_surface_band_px = 16;       // rows per band in which the road's residual peak is found [px]
  float lowest_surface_min_fraction = 0.1f;  // share of its band the road peak must hold within the tolerance
  float lowest_surface_tolerance = 0.035f;   // relative residual (d - d_plane) / d around the peak that is road
  int lowest_surface_passes = 2;         // selections, each from the plane fitted to the previous one
  float residual_entropy_bin = 0.01f;    // entropy bin of the relative plane residuals (d - d_plane) / d

  // Instant pitch source (docs/snv.md "pitch_oscillation"): "plane" = a second robust plane
  // fit (ground_plane_fit.hpp) on the ground samples inside the super-SNV mean-shift window,
  // started from the mean-shift pitch and the plane roll, kept when it is within
  // the gate (plane_pitch_gate_deg, widened below) of the mean shift (else the mean shift); "mean_shift" = the super-SNV
  // mean-shift value; "slope" = robust fit of the samples' normalised vertical slopes
  // (slope_pitch.hpp; linear in the noise, but the matchers' local slopes are biased low).
  std::string pitch_source = "plane";
  bool plane_pitch_inliers_only = true;  // "plane": only samples inside the mean-shift window
  float plane_pitch_gate_deg = 0.5f;     // "plane": keep the mean shift when the plane differs by more [deg]
  // ... or by more than this share of the mean-shift window's half-width, if that is wider: the
  // mean shift's own bias grows with the spread of the per-normal pitch (a short-baseline
  // camera: ZED 3.1-3.8 deg half-width, mean shift 0.4-1.0 deg off, the plane within 0.05 deg;
  // KITTI geometry 1.1-2.0 deg; docs/snv.md "Short baselines").
  float plane_pitch_gate_radius_share = 0.35f;
  bool slope_inliers_only = false;       // "slope": only samples inside the mean-shift window
  bool slope_mean_shift = false;         // "slope": location by adaptive mean shift instead of Tukey
  float slope_tukey_k = 4.685f;          // "slope": biweight cut-off in robust sigmas

  // Pose quality and filter.
  float entropy_full_scale_bits = 6.0f;  // confidence = 1 - H / this
  float min_confidence = 0.05f;          // below: status "low_confidence", pose not used
  float min_height_m = 0.3f;             // heights outside [min, max] are rejected [m]
  float max_height_m = 5.0f;
  float filter_roll_process_var_deg2 = 0.05f;   // roll random walk per frame [deg^2]
  float filter_height_process_var_m2 = 1e-4f;   // height random walk per frame [m^2]
  float filter_pitch_meas_var_deg2 = 0.01f;     // one frame's pitch variance [deg^2] (docs/snv.md "Filter")
  float filter_roll_meas_var_deg2 = 0.01f;      // one frame's roll variance [deg^2] (docs/snv.md "Filter")
  float filter_height_meas_var_m2 = 1e-4f;      // one frame's height variance [m^2] (docs/snv.md "Filter")
  bool filter_adaptive = true;                  // inflate the prior to the innovation when it is larger (tracks swings)

  // ROI classes (roi_normal_stats.hpp).
  float upright_tolerance_deg = 30.0f;          // 90 +- this from the ground normal = upright
  float facing_cone_deg = 10.0f;                // within this of the camera -z axis = facing
  float upright_consistency_fraction = 0.15f;   // upright share that makes facing normals object-like
};

Params readParams(ConfigSection& section);
// The integral-normal part of the parameters (what process() prepares its field with).
IntegralNormalParams normalParams(const Params& params);
// The ground-sample part of the parameters.
GroundSampleParams groundParams(const Params& params);

struct SnvResult {
  PoseEstimate pose;              // instant values and the temporally filtered ones
  float ground_normal[3] = {0, -1, 0};
  int ground_samples = 0;
  int interval_px = 0;
  std::vector<NormalStats> rois;  // one per input hypothesis, same order
};

class SnvExtrinsicEstimator {
 public:
  explicit SnvExtrinsicEstimator(const Params& params);
  // disparity: CV_32F, <= 0 invalid. rois: the STIXELS hypotheses of the same
  // frame. ground: the stixel stage's road model (may be invalid).
  // Keeps the temporal filter's state between calls.
  SnvResult process(const cv::Mat& disparity, const StereoCamera& cam,
                    const std::vector<Hypothesis>& rois, const GroundModel& ground);
  // Forgets the temporal filter's state (the buffers stay): the next frame is
  // estimated as the first one of a fresh estimator is.
  void resetFilter();

 private:
  Params params_;
  PoseFilter filter_;
  LocalFields fields_;  // kept across frames so their integral buffers are reused
};

}  // namespace nerv::snv

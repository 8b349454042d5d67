// Surface normal vectors from disparity, super-SNV camera pose and per-ROI
// normal statistics (NERV reference slides 11-28). No transport here.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "config.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv {

struct Params {
  int interval_px = 4;                 // sampling interval of the local normals [px]
  float histogram_bin_deg = 0.1f;      // pitch histogram bin
  float mean_shift_stop_deg = 0.01f;   // mean shift stops when it moves less than this
  float mean_shift_fraction = 0.5f;    // adaptive radius holds this fraction of the vectors
  float ground_tolerance_deg = 15.0f;  // normal within this of the ground normal = ground-like
  float filter_process_var_deg2 = 0.05f;  // temporal filter: pitch random walk per frame
};

Params readParams(ConfigSection& section);

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

 private:
  Params params_;
  struct FilterState { bool initialised = false; float pitch = 0, roll = 0, height = 0, var = 1; };
  FilterState filter_;
};

}  // namespace nerv::snv

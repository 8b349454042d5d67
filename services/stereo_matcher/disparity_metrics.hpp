// Scoring a disparity map against ground truth, as the public benchmarks do:
// KITTI 2015 D1 (|d - gt| > 3 px and > 5 % of gt) and Middlebury bad-2.0
// (|d - gt| > 2 px). Invalid estimates are first filled by the KITTI devkit's
// background interpolation, so a sparse map is not rewarded for leaving hard
// pixels out; the density of the original estimate is reported with the score.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace nerv::stereo {

// KITTI devkit background interpolation on a CV_32F map (<= 0 invalid), in place:
// per row, each invalid run between two valid pixels takes the smaller (farther)
// of its two neighbours; runs touching the left/right border take the nearest
// valid value of the row; then per column the first valid value is copied up
// to the top and the last down to the bottom (an empty row between valid rows
// stays invalid and is scored as wrong, as in the devkit).
void interpolateBackground(cv::Mat& disparity);

struct DisparityScore {
  double error_rate = 0;  // fraction of ground-truth pixels that are wrong (after interpolation)
  double density = 0;     // fraction of ground-truth pixels the estimate had a value for
  long long pixels = 0;   // ground-truth pixels scored
  // Subpixel accuracy: mean |d - gt| over the estimate's own valid pixels within
  // 1 px of the truth (before interpolation), and how many of them there were.
  double inlier_mean_error = 0;
  long long inliers = 0;
  // Their mean signed error d - gt: a disparity offset (a rig turned since calibration, or the
  // matcher's own bias), which the absolute error and the error rate cannot show.
  double inlier_mean_bias = 0;
};

// estimate, ground_truth: CV_32F [px], ground truth <= 0 = unknown.
DisparityScore scoreD1(const cv::Mat& estimate, const cv::Mat& ground_truth);
DisparityScore scoreBad(const cv::Mat& estimate, const cv::Mat& ground_truth, double threshold_px);

// Ground-truth PNG: 16-bit = KITTI (value / 256, kind "kitti"), 8-bit =
// Middlebury (value in px, kind "middlebury"); 0 = unknown. Throws cv::Exception
// (via CV_Error) when the file cannot be read.
cv::Mat loadGroundTruth(const std::string& path, std::string& kind);

// Frames of a folder with left/, right/ and disp_gt/ (plain layout) or
// image_2/, image_3/ and disp_occ_0/ (KITTI stereo/object layout, as the
// synthetic generator writes), same stems, any image extension; frames without
// ground truth are skipped. Sorted by name.
struct EvalFrame {
  std::string name, left_path, right_path, gt_path;
};
std::vector<EvalFrame> findEvalFrames(const std::string& dir);

}  // namespace nerv::stereo

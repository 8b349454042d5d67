// When to run the stereo_matcher's checks of its rig, and what they say: one camera stopped
// (frozen_view.hpp) on every frame; the rows (rectification_check.hpp) on the first 10 frames
// and then every check_every frames, and when they cannot be measured, a blank view
// (blank_view.hpp) or swapped views (view_order_check.hpp). A check that reads the rows on
// the other side of the limit from the last verdict (a rig knocked mid-drive, or mended)
// makes the next checks run on every frame, and the verdict is of those alone: it comes
// 10-19 frames after the knock instead of the 60-160 a window of every-tenth-frame checks
// needed to turn. On the same frames, while driving, the vehicle's forward step from the
// frame before is the reference for two more: whether the two views were taken at the same
// moment (shutter_sync.hpp) and whether every disparity is off by the same amount
// (disparity_offset.hpp); two readings in a row against the last verdict of either make the
// checks run on every frame until a verdict of those readings alone (change_watch.hpp), 11-20
// frames after a trigger lost or a camera turned mid-drive. A row verdict that finds the
// matched views' rows off by more than row_correction_above_px sets the correction the right
// views are resampled with from the next frame on (view_correction.hpp) and checks the next
// 10 frames; an offset verdict beyond its limit likewise has the offset taken off every
// disparity. Both are then said against the calibration (the correction plus what is left),
// so the errors that ask for a recalibration stay. The service reports what comes
// back: counters, errors and log lines; this keeps no transport and is tested on its own.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "change_watch.hpp"
#include "disparity_offset.hpp"
#include "frozen_view.hpp"
#include "rectification_check.hpp"
#include "view_correction.hpp"
#include "shutter_sync.hpp"

#include <cstdint>

namespace nerv::stereo {

struct RigCheckParams {
  int check_every = 10;         // frames between row checks after the first ones; 0 = no row checks
  int first_checks = 10;        // checks on each of the first frames, so the first verdict comes early
  float max_row_offset_px = 0.4f;
  bool row_correction = true;            // resample the right views by the rows measured off (view_correction.hpp)
  float row_correction_above_px = 0.25f;  // ... once what the matcher sees of them is beyond this where it matches
  float max_row_correction_px = 5.0f;     // at most this far anywhere in the view (the rest stays an error)
  int frozen_after = 3;         // pairs in a row with one view repeated before it is said
  int faults_in_a_row = 2;      // blank or swapped views: checks in a row before it is said
  float max_view_delay_ms = 2.0f;  // the right view taken more than this before or after the left: an error
  float max_disparity_offset_px = 0.6f;  // every disparity off by more than this either way: an error
  bool offset_correction = true;          // ... and taken off every disparity (view_correction.hpp)
  float max_offset_correction_px = 3.0f;  // by at most this much
};

// What the checks against the vehicle's motion need of a matched pair besides its views: when
// it was taken and the rectified camera. fx = 0: no such checks.
struct PairTiming {
  int64_t utime_us = 0;  // capture time [us]
  double fx = 0, cx = 0, cy = 0;
  double baseline_m = 0;  // to say what an offset costs at 40 m (0: not said)
};

struct RigFinding {
  enum class Kind { Count, Error, Log, Gauge };
  Kind kind;
  std::string name;     // the counter (Count, Error) or the gauge, its unit in the name (Gauge)
  std::string message;  // one line (Error, Log)
  double value = 0;     // the gauge's value (Gauge): what a verdict decided on
};

class RigCheck {
 public:
  explicit RigCheck(const RigCheckParams& params = {});
  // Every accepted pair, as decoded, before it is matched.
  std::vector<RigFinding> beforeMatching(const cv::Mat& left, const cv::Mat& right);
  // The right view to match (8-bit gray): as it is, or resampled by the row correction the
  // verdicts so far have set (valid until the next call).
  const cv::Mat& rightToMatch(const cv::Mat& right) { return correction_.apply(right); }
  // The matcher's disparity (CV_32F) with the offset correction the verdicts have set taken off.
  void correctDisparity(cv::Mat& disparity) const { correction_.correctDisparity(disparity); }
  const RowPlane& rowCorrection() const { return correction_.rows(); }
  // Corrections of an earlier run for the same calibration (rig_state.hpp), applied from the
  // next pair on as far as this configuration corrects (row_correction, offset_correction, their
  // largest); the first verdicts keep, change or drop them as any other. True when any was set.
  bool restore(const RowPlane& rows, double offset_px, cv::Size size);
  double offsetCorrection() const { return correction_.columns(); }
  // Every matched pair: the gray views the matcher saw and its disparity (CV_32F).
  std::vector<RigFinding> afterMatching(const cv::Mat& left, const cv::Mat& right, const cv::Mat& disparity,
                                        const PairTiming& timing = {});

 private:
  // At a row verdict: sets, changes or drops the correction; true when it changed.
  bool correctRows(const RowOffset& median, cv::Size size, std::vector<RigFinding>& out);
  // A correction as far as max_row_correction_px / max_offset_correction_px let it go.
  RowPlane cappedRows(const RowPlane& rows, cv::Size size) const;
  double cappedOffset(double offset_px) const;
  // At an offset verdict: sets, changes or drops the columns' correction; true when it changed.
  bool correctOffset(float left_over, float e, std::vector<RigFinding>& out);
  void checkAgainstMotion(int previous, const cv::Mat& right, const cv::Mat& disparity, const PairTiming& timing,
                          std::vector<RigFinding>& out);
  // A motion reading against its last verdict: the next frame checked too, or the window forgotten
  // and every frame checked until the next verdict (change_watch.hpp), counted as `counter`.
  void watch(ChangeWatch& watch, MedianVerdict& window, float reading, const char* what, const char* unit,
             const char* counter, std::vector<RigFinding>& out);

  RigCheckParams p_;
  FrozenViewCheck frozen_;
  RowOffsetMonitor rows_;
  ViewCorrection correction_;
  long long frames_ = 0, checks_ = 0;
  // An aligned verdict is logged the first time, after an error, and whenever the rows moved
  // by 0.1 px or more since the last such line, so a drift shows before it is an error.
  float worst_said_ = -1.0f;
  enum class Verdict { None, Aligned, Misaligned } verdict_ = Verdict::None;
  float verdict_worst_ = 0;  // the last verdict's median of the worst offsets the matcher saw [px]
  int check_next_ = 0;       // frames still checked, each: after a reading against a verdict
  int row_burst_left_ = 0;   // row checks still to come of a burst after a row reading against the verdict
  // The shutter check compares with the previous matched left view: two buffers, alternated,
  // so that keeping one costs a copy and no allocation.
  cv::Mat lefts_[2];
  int64_t utimes_[2] = {0, 0};
  int newest_ = -1;
  MedianVerdict delays_, offsets_;
  ChangeWatch delay_watch_, offset_watch_;
  bool unsynchronised_ = false;
  float delay_said_ = 1e9f;   // the delay of the last "synchronised" line [ms]
  float offset_said_ = 1e9f;  // the offset of the last "consistent" line [px]
  int blank_in_a_row_ = 0, swapped_in_a_row_ = 0;
};

}  // namespace nerv::stereo

// The rig's corrections kept across restarts. The stereo_matcher corrects a rig that has left
// its calibration (view_correction.hpp) only after its first verdicts: the rows from the 11th
// frame, the disparity offset from the 21st while driving. A service restarted by nerv_up or
// systemd, or a vehicle started in the morning, would match its first frames uncorrected every
// time (KITTI 0926 a row off: F1 0.45 instead of 0.82). With stereo_matcher.rig_state_file set,
// each verdict that sets, changes or drops a correction writes it to that file (YAML, written to
// a temporary file and renamed, so a reader never sees half of it), with the calibration it was
// measured under; the next start applies it from its first frame when the frames' calibration
// is that one, bit for bit. The first verdicts then check it as ever: kept while the rig reads
// the same, changed or dropped when it does not. A file of another calibration (the rig
// recalibrated since) is left unused and said once; a file that cannot be read is an error
// that names it, and the matcher starts uncorrected. This keeps no transport: the service
// hands it the calibration's fingerprint and reports what it returns.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rig_check.hpp"
#include "row_plane.hpp"

namespace nerv::stereo {

// The calibration a correction was measured under: a fingerprint of every field the frames
// carry (the service's: FNV-1a over the encoded stereo_calibration_t), and the ones a person
// reads, to say what differs.
struct RigCalibration {
  uint64_t fingerprint = 0;
  int width = 0, height = 0;
  double fx = 0, cx = 0, cy = 0, baseline_m = 0;
  bool rectified = true;
};

struct RigState {
  RigCalibration calibration;
  RowPlane rows;            // the right views' row correction (view_correction.hpp)
  double offset_px = 0;     // the disparity offset taken off
  std::string saved_utc;    // when it was written, ISO 8601
};

// Reads path. Returns "" and fills state, or the one-line problem (a missing or unknown key, a
// value that is not a finite number, not YAML). absent: the file does not exist (no problem).
std::string readRigState(const std::string& path, RigState& state, bool& absent);
// Writes state to path through path.tmp.<pid> and a rename. Returns "" or the problem.
std::string writeRigState(const std::string& path, const RigState& state);
// "" when the two are the same calibration, else what differs ("fx 721.50 against 718.86").
std::string calibrationDifference(const RigCalibration& saved, const RigCalibration& now);

// The file's part in the service: restore at the first frame, save when a correction changes.
class RigStateKeeper {
 public:
  explicit RigStateKeeper(std::string path) : path_(std::move(path)) {}
  bool enabled() const { return !path_.empty(); }
  // The frame's calibration and the time (ISO 8601), asked for only when they are used: at the
  // first frame and when a correction is written, not on every frame.
  using CalibrationOf = std::function<RigCalibration()>;
  using Now = std::function<std::string()>;
  // Every accepted frame before it is matched; only the first does anything: reads the file
  // and, for this calibration, restores its corrections into rig.
  std::vector<RigFinding> beforeMatching(const CalibrationOf& calibration, RigCheck& rig);
  // Every matched frame after the rig's checks: writes the corrections when they differ from
  // what the file holds.
  std::vector<RigFinding> afterMatching(const CalibrationOf& calibration, const RigCheck& rig, const Now& now_utc);

 private:
  std::string path_;
  bool started_ = false;
  bool held_ = false;  // saved_ is what the file holds (restored, written, or last tried)
  RigState saved_;
};

}  // namespace nerv::stereo

#include "rig_state.hpp"

#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include <opencv2/core.hpp>

#include "config.hpp"

namespace nerv::stereo {

namespace {

// Every key the file must have, and only those (a file of another layout is not guessed at).
double required(ConfigSection& s, const std::string& key, double lo, double hi) {
  if (!s.has(key)) throw ConfigError("key '" + (s.path().empty() ? key : s.path() + "." + key) + "' is missing");
  double v = 0;
  s.get(key, v, lo, hi);
  return v;
}

// A key the file must not have is named before a key it lacks: a misspelt key says so.
void onlyKeys(ConfigSection& s, std::initializer_list<const char*> keys) {
  for (const char* k : keys) s.allow(k);
  s.finish();
}

std::string number(double v) { return cv::format("%.17g", v); }

bool samePlane(const RowPlane& a, const RowPlane& b) {
  return a.offset_px == b.offset_px && a.slope_x == b.slope_x && a.slope_y == b.slope_y;
}

}  // namespace

std::string readRigState(const std::string& path, RigState& state, bool& absent) {
  absent = false;
  std::ifstream probe(path);
  if (!probe) {
    if (errno == ENOENT) {
      absent = true;
      return "";
    }
    return "rig state file " + path + " cannot be read: " + std::strerror(errno);
  }
  try {
    ConfigSection top(loadConfigFile(path), "");
    onlyKeys(top, {"saved_utc", "calibration", "row_correction", "offset_correction_px"});
    RigState s;
    std::string fingerprint;
    ConfigSection cal = top.section("calibration");
    onlyKeys(cal, {"fingerprint", "width", "height", "fx", "cx", "cy", "baseline_m", "rectified"});
    if (!cal.has("fingerprint")) throw ConfigError("key 'calibration.fingerprint' is missing");
    cal.get("fingerprint", fingerprint);
    char* end = nullptr;
    s.calibration.fingerprint = std::strtoull(fingerprint.c_str(), &end, 16);
    if (fingerprint.empty() || *end != 0)
      throw ConfigError("key 'calibration.fingerprint' must be hexadecimal, got '" + fingerprint + "'");
    s.calibration.width = static_cast<int>(required(cal, "width", 1, 1 << 16));
    s.calibration.height = static_cast<int>(required(cal, "height", 1, 1 << 16));
    s.calibration.fx = required(cal, "fx", 1e-6, 1e9);
    s.calibration.cx = required(cal, "cx", -1e9, 1e9);
    s.calibration.cy = required(cal, "cy", -1e9, 1e9);
    s.calibration.baseline_m = required(cal, "baseline_m", 1e-9, 1e6);
    if (!cal.has("rectified")) throw ConfigError("key 'calibration.rectified' is missing");
    cal.get("rectified", s.calibration.rectified);
    ConfigSection rows = top.section("row_correction");
    onlyKeys(rows, {"offset_px", "slope_x", "slope_y"});
    s.rows.offset_px = required(rows, "offset_px", -100, 100);
    s.rows.slope_x = required(rows, "slope_x", -1, 1);
    s.rows.slope_y = required(rows, "slope_y", -1, 1);
    s.offset_px = required(top, "offset_correction_px", -100, 100);
    top.get("saved_utc", s.saved_utc);
    state = s;
    return "";
  } catch (const ConfigError& e) {
    // loadConfigFile names the file itself; the key checks do not.
    const std::string what = e.what();
    if (what.rfind("config file ", 0) == 0) return "rig state " + what.substr(7);
    return "rig state file " + path + ": " + what;
  } catch (const YAML::Exception& e) {
    return "rig state file " + path + ": " + e.msg;
  } catch (const std::exception& e) {  // the stream's own (a folder where the file should be)
    return "rig state file " + path + " cannot be read: " + e.what();
  }
}

std::string writeRigState(const std::string& path, const RigState& state) {
  const std::string tmp = path + ".tmp." + std::to_string(getpid());
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) return "rig state file " + tmp + " cannot be written: " + std::strerror(errno);
    const RigCalibration& c = state.calibration;
    out << "# The stereo_matcher's corrections of this rig (stereo_matcher.rig_state_file), restored at its\n"
           "# next start for frames of this calibration. Written by nerv; delete it to start uncorrected.\n"
        << "saved_utc: \"" << state.saved_utc << "\"\n"
        << "calibration:\n"
        << cv::format("  fingerprint: \"%016" PRIx64 "\"\n", c.fingerprint) << "  width: " << c.width << "\n"
        << "  height: " << c.height << "\n"
        << "  fx: " << number(c.fx) << "\n"
        << "  cx: " << number(c.cx) << "\n"
        << "  cy: " << number(c.cy) << "\n"
        << "  baseline_m: " << number(c.baseline_m) << "\n"
        << "  rectified: " << (c.rectified ? "true" : "false") << "\n"
        << "row_correction:        # the right views resampled: dy = offset + slope_x (x - W/2) + slope_y (y - H/2)\n"
        << "  offset_px: " << number(state.rows.offset_px) << "\n"
        << "  slope_x: " << number(state.rows.slope_x) << "\n"
        << "  slope_y: " << number(state.rows.slope_y) << "\n"
        << "offset_correction_px: " << number(state.offset_px) << "   # taken off every disparity\n";
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      return "rig state file " + tmp + " cannot be written: " + std::strerror(errno);
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    return "rig state file " + path + " cannot be replaced: " + why;
  }
  return "";
}

std::string calibrationDifference(const RigCalibration& saved, const RigCalibration& now) {
  if (saved.fingerprint == now.fingerprint) return "";
  if (saved.width != now.width || saved.height != now.height)
    return cv::format("%dx%d against %dx%d", saved.width, saved.height, now.width, now.height);
  if (saved.rectified != now.rectified)
    return saved.rectified ? "rectified frames against raw ones" : "raw frames against rectified ones";
  if (saved.fx != now.fx) return cv::format("fx %.2f against %.2f", saved.fx, now.fx);
  if (saved.cx != now.cx) return cv::format("cx %.2f against %.2f", saved.cx, now.cx);
  if (saved.cy != now.cy) return cv::format("cy %.2f against %.2f", saved.cy, now.cy);
  if (saved.baseline_m != now.baseline_m)
    return cv::format("baseline %.4f m against %.4f m", saved.baseline_m, now.baseline_m);
  return "the same focal length, centre and baseline but other fields (fy, distortion or the cameras' pose)";
}

std::vector<RigFinding> RigStateKeeper::beforeMatching(const CalibrationOf& calibration_of, RigCheck& rig) {
  std::vector<RigFinding> out;
  if (!enabled() || started_) return out;
  started_ = true;
  const RigCalibration calibration = calibration_of();
  RigState state;
  bool absent = false;
  const std::string problem = readRigState(path_, state, absent);
  if (!problem.empty()) {
    out.push_back({RigFinding::Kind::Error, "bad_rig_state",
                   problem + "; not used: the rig's corrections are measured again by the first verdicts"});
    return out;
  }
  if (absent) {
    out.push_back({RigFinding::Kind::Log, "",
                   "rig state: " + path_ + " does not exist yet; it is written at the first correction"});
    return out;
  }
  const std::string differs = calibrationDifference(state.calibration, calibration);
  if (!differs.empty()) {
    out.push_back({RigFinding::Kind::Count, "rig_state_other_calibration", ""});
    out.push_back({RigFinding::Kind::Log, "",
                   "rig state: " + path_ + " (saved " + state.saved_utc + ") is of another calibration (" + differs +
                       "): not used; it is replaced at the first correction"});
    return out;
  }
  const cv::Size size(calibration.width, calibration.height);
  if (!rig.restore(state.rows, state.offset_px, size)) {
    // Corrections switched off here (or none saved): the file is left as it is for a run that applies them.
    out.push_back({RigFinding::Kind::Log, "", "rig state: " + path_ + " (saved " + state.saved_utc +
                                                  ") holds no correction this configuration applies"});
    return out;
  }
  held_ = true;
  saved_ = state;  // as applied: a correction switched off here is not in it, nor kept at the next write
  saved_.rows = rig.rowCorrection();
  saved_.offset_px = rig.offsetCorrection();
  out.push_back({RigFinding::Kind::Count, "rig_state_restored", ""});
  std::string does;
  if (!rig.rowCorrection().zero())
    does = cv::format("the right views are resampled by %.2f px at most", rig.rowCorrection().largestOver(size));
  if (rig.offsetCorrection() != 0)
    does += std::string(does.empty() ? "" : " and ") +
            (rig.offsetCorrection() > 0 ? cv::format("%.2f px is taken off every disparity", rig.offsetCorrection())
                                        : cv::format("%.2f px is added to every disparity", -rig.offsetCorrection()));
  out.push_back({RigFinding::Kind::Log, "",
                 "rig state: from the first frame " + does + ", as saved in " + path_ + " at " + state.saved_utc +
                     "; the first verdicts check it"});
  out.push_back({RigFinding::Kind::Gauge, "row_correction_px", "", rig.rowCorrection().largestOver(size)});
  out.push_back({RigFinding::Kind::Gauge, "offset_correction_px", "", rig.offsetCorrection()});
  return out;
}

std::vector<RigFinding> RigStateKeeper::afterMatching(const CalibrationOf& calibration, const RigCheck& rig,
                                                      const Now& now_utc) {
  std::vector<RigFinding> out;
  if (!enabled()) return out;
  // Written when a correction changes, with the calibration of the frames it was measured on; a
  // calibration that changes mid-run alone writes nothing (the corrections are still the old camera's).
  const bool same = held_ && samePlane(saved_.rows, rig.rowCorrection()) && saved_.offset_px == rig.offsetCorrection();
  // Nothing corrected and no file of this calibration to update: nothing to keep.
  if (same || (!held_ && rig.rowCorrection().zero() && rig.offsetCorrection() == 0)) return out;
  RigState state{calibration(), rig.rowCorrection(), rig.offsetCorrection(), now_utc()};
  const std::string problem = writeRigState(path_, state);
  if (!problem.empty()) {
    out.push_back({RigFinding::Kind::Error, "rig_state_not_saved",
                   problem + "; the corrections apply in this run, the next start measures them again"});
    // Tried again at the next change, not every frame.
  } else {
    out.push_back({RigFinding::Kind::Count, "rig_state_saved", ""});
  }
  held_ = true;
  saved_ = state;
  return out;
}

}  // namespace nerv::stereo

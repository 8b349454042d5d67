// The run report of `nerv_report`: one self-contained HTML page made from a
// log alone (plus KITTI labels when given): run summary, pose over time,
// detections per frame, a frame's pitch distribution with the three
// estimates of EXTRINSICS, per-stage timing, precision/recall and the worst
// frames rendered.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "detection_eval.hpp"
#include "log_frames.hpp"

namespace nerv::viz {

struct ReportOptions {
  std::string out_dir;          // report.html is written here
  std::string labels_dir;       // KITTI label_2 folder; empty: no evaluation
  std::string extrinsics_file;  // "frame pitch_deg roll_deg height_m" lines; empty: DIR/../extrinsics.txt if present
  int64_t histogram_seq = -1;   // frame of the pitch histogram; -1: the middle frame with a valid pose
  int worst_frames = 3;         // rendered frames with the most errors (labels only)
  EvalParams eval;
  std::optional<std::string> prefix;  // the pipeline (channel prefix) to report; unset: the first in the log
};

struct ReportResult {
  std::string html_path;
  int frames = 0;               // frames seen in the log (any message)
  int images = 0;               // images embedded
  int plots = 0;                // SVG plots embedded
  LogReadStats log;
  std::string note;             // one line about something missing (e.g. no STEREO_FRAME), or empty
};

// Throws std::runtime_error for an unreadable log or output folder.
ReportResult writeRunReport(const std::string& log_path, const ReportOptions& options);

}  // namespace nerv::viz

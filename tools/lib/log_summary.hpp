// The summary of one pipeline run, computed from its LCM log alone.
#pragma once

#include <string>

namespace nerv {

// Reads the log and returns the summary as a JSON document: frames in/out,
// fps, end-to-end latency p50/p95 (logger receive time of DETECTIONS minus the
// capture utime), per-stage processing time, detections per frame, pitch and
// height per frame. Throws std::runtime_error when the log cannot be read.
std::string summarizeLog(const std::string& log_path, std::string* text_report = nullptr);

}  // namespace nerv

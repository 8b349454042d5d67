// The summary of one pipeline run, computed from its LCM log alone.
#pragma once

#include <optional>
#include <string>

namespace nerv {

// Reads the log and returns the summary as a JSON document: frames in/out,
// fps, end-to-end latency p50/p95 (logger receive time of DETECTIONS minus the
// capture utime), per-stage processing time, detections per frame, pitch and
// height per frame. Of a log holding several pipelines (channel prefixes, one per camera), only
// the pipeline of `prefix`, else the first in the log; the JSON names it ("prefix") and every
// pipeline of the log ("prefixes"), and the text report says when there are several. Throws
// std::runtime_error when the log cannot be read or holds no channel of `prefix`.
std::string summarizeLog(const std::string& log_path, std::string* text_report = nullptr,
                         const std::optional<std::string>& prefix = std::nullopt);

}  // namespace nerv

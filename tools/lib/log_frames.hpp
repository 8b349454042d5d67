// Reads an LCM log into frames: every message of one seq (stereo pair,
// disparity, stixels, normals, extrinsics, detections) gathered in one struct.
// Types are recognised by their fingerprint, so channel prefixes do not matter.
// The reader streams: frames come out in seq order, the oldest as soon as it
// holds all six messages, or when more than `max_pending` frames wait (a log
// without some channel, a lost message) or at the end of the log, so memory
// stays bounded on long logs.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "pipeline_prefix.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

#include "message_fingerprint.hpp"  // messageFingerprint, which the readers of logs use

namespace nerv {

struct LogFrame {
  int64_t seq = 0;
  std::string frame_id;
  std::optional<stereo_frame_t> stereo;
  std::optional<disparity_t> disparity;
  std::optional<stixels_t> stixels;
  std::optional<surface_normals_t> normals;
  std::optional<extrinsics_t> extrinsics;
  std::optional<detections_t> detections;
  int64_t stereo_log_utime = -1;      // logger receive time of STEREO_FRAME [us]
  int64_t detections_log_utime = -1;  // ... and of DETECTIONS [us]
};

struct LogReadStats {
  int64_t events = 0;          // events read
  int64_t frame_messages = 0;  // decoded frame messages (the six types above)
  int64_t other_messages = 0;  // valid events of other types (health, unknown channels)
  int64_t broken = 0;          // a known fingerprint that did not decode: skipped
  int64_t duplicates = 0;      // a second message of the same type and seq: skipped
  int64_t stereo_frames = 0;   // STEREO_FRAME messages seen (0: the log cannot be rendered)
  int64_t other_pipeline = 0;  // frame messages of another camera's pipeline (channel prefix): skipped
  std::string pipelines;       // at the end: one line when the log holds several (pipeline_prefix.hpp)
  std::map<std::string, int64_t> broken_per_channel;
};

struct LogFrameOptions {
  int64_t seq_min = std::numeric_limits<int64_t>::min();  // frames outside [min, max] are skipped
  int64_t seq_max = std::numeric_limits<int64_t>::max();
  std::set<int64_t> seqs;      // non-empty: only these frames
  bool keep_images = true;     // false: stereo and disparity pixels are dropped on read
  std::optional<std::string> prefix;  // the pipeline (channel prefix) to read; unset: the first in the log
  int max_pending = 16;        // incomplete frames held before the oldest is handed out
};

class LogFrameReader {
 public:
  // Throws std::runtime_error naming the path when the log cannot be opened.
  LogFrameReader(const std::string& path, const LogFrameOptions& options = {});
  ~LogFrameReader();
  // The next frame in seq order of completion; false at the end of the log.
  bool next(LogFrame& frame);
  const LogReadStats& stats() const { return stats_; }

 private:
  void absorb(const lcm::LogEvent& e);
  bool popReady(LogFrame& frame, bool flush);

  std::unique_ptr<lcm::LogFile> log_;
  LogFrameOptions options_;
  LogReadStats stats_;
  std::map<int64_t, LogFrame> pending_;
  PipelineSelection pipeline_;
  std::set<int64_t> handed_out_;        // seqs already returned (late messages are duplicates)
  bool eof_ = false;
};

}  // namespace nerv

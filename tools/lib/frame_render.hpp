// Renders the frames of a log to NNNNNN.png (and optionally one video), the
// whole of `nerv_render` but the flags, so tests can call it directly.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "frame_grid.hpp"
#include "log_frames.hpp"

namespace nerv::viz {

struct RenderOptions {
  std::string out_dir;
  int64_t seq_min = std::numeric_limits<int64_t>::min();
  int64_t seq_max = std::numeric_limits<int64_t>::max();
  std::string labels_dir;       // KITTI label_2 folder; empty: no ground truth
  bool video = false;           // also write out_dir/render.avi (MJPG)
  double video_fps = 10;
  double scale = 1.0;           // output scale of the grid (1 = left image size per panel)
  NeedleParams needles;
  std::optional<std::string> prefix;  // the pipeline (channel prefix) to draw; unset: the first in the log
};

struct RenderResult {
  int rendered = 0;             // PNGs written
  int skipped = 0;              // frames without a usable left image (see `problems`)
  int label_problems = 0;       // label files that could not be read
  LogReadStats log;             // what the reader saw (broken messages, duplicates, ...)
  std::string first_problem;    // the first skipped frame's reason
  std::string video_path;       // empty when no video was written
  double seconds = 0;
};

// Throws std::runtime_error for a log that cannot be read or an output folder
// that cannot be made; every problem inside the log is counted, not thrown.
RenderResult renderLog(const std::string& log_path, const RenderOptions& options);

// Label file of a frame: DIR/<last part of frame_id>.txt (empty when absent).
std::string labelFileFor(const std::string& labels_dir, const std::string& frame_id);

}  // namespace nerv::viz

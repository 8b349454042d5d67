// Which pipeline of a log an event belongs to. A vehicle with several cameras runs a nerv
// pipeline per camera on one bus, each under its channel prefix (FRONT_DISPARITY,
// REAR_DISPARITY), and one lcm-logger records them all. Frames of the pipelines share their
// sequence numbers, so a tool that merged them by seq counted one camera's frames as the
// other's: the log tools read one pipeline at a time, the one asked for or the first in the log.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace nerv {

// The prefix of a nerv channel ("FRONT_" for FRONT_DISPARITY, "" for DISPARITY); nullopt
// when the channel does not end with one of nerv's channel names.
std::optional<std::string> nervChannelPrefix(const std::string& channel);
// The same for the channels of a pipeline's frames (STEREO_FRAME ... DETECTIONS), not
// NERV_HEALTH: a prefix whose only channel is NERV_HEALTH (a probe's, a stray tool's) is no
// pipeline.
std::optional<std::string> framePipelinePrefix(const std::string& channel);

class PipelineSelection {
 public:
  // wanted: the prefix to read; nullopt: the first pipeline whose channel the log holds.
  explicit PipelineSelection(std::optional<std::string> wanted = std::nullopt) : wanted_(std::move(wanted)) {}

  // Whether an event of this frame channel belongs to the selected pipeline, the first frame
  // channel deciding which that is when none was asked for (NERV_HEALTH and channels that are
  // no nerv channel belong to every one: callers keep health by its prefix and read the selected one at the end).
  bool take(const std::string& channel);

  // The prefixes of the pipelines seen, in the order of their first frame event.
  const std::vector<std::string>& prefixes() const { return prefixes_; }
  // The prefix read ("" also when the log held no nerv channel).
  std::string selected() const { return wanted_ ? *wanted_ : (prefixes_.empty() ? "" : prefixes_.front()); }
  // One line when the log holds several pipelines ("this log holds 2 pipelines, by channel
  // prefix: 'FRONT_' (read here), 'REAR_'; choose one with --prefix P"), else "". Throws
  // std::runtime_error when the wanted prefix is not in the log.
  std::string note() const;

 private:
  std::optional<std::string> wanted_;
  std::vector<std::string> prefixes_;
};

}  // namespace nerv

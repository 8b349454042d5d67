#include "pipeline_prefix.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace nerv {

namespace {
const char* const kChannels[] = {"STEREO_FRAME", "DISPARITY",  "STIXELS",    "SURFACE_NORMALS",
                                 "EXTRINSICS",   "DETECTIONS", "NERV_HEALTH"};
constexpr int kFrameChannels = 6;  // the first six

std::optional<std::string> prefixAmong(const std::string& channel, int count) {
  for (int i = 0; i < count; ++i) {
    const std::string n(kChannels[i]);
    if (channel.size() >= n.size() && channel.compare(channel.size() - n.size(), n.size(), n) == 0)
      return channel.substr(0, channel.size() - n.size());
  }
  return std::nullopt;
}

// 'FRONT_' (read here), 'REAR_'
std::string quotedList(const std::vector<std::string>& v, const std::string* marked) {
  std::string s;
  for (const auto& p : v) s += (s.empty() ? "'" : ", '") + p + "'" + (marked && p == *marked ? " (read here)" : "");
  return s;
}
}  // namespace

std::optional<std::string> nervChannelPrefix(const std::string& channel) {
  return prefixAmong(channel, static_cast<int>(std::size(kChannels)));
}

std::optional<std::string> framePipelinePrefix(const std::string& channel) { return prefixAmong(channel, kFrameChannels); }

bool PipelineSelection::take(const std::string& channel) {
  const auto prefix = framePipelinePrefix(channel);
  if (!prefix) return true;
  if (std::find(prefixes_.begin(), prefixes_.end(), *prefix) == prefixes_.end()) prefixes_.push_back(*prefix);
  return *prefix == selected();
}

std::string PipelineSelection::note() const {
  if (wanted_ && !prefixes_.empty() && std::find(prefixes_.begin(), prefixes_.end(), *wanted_) == prefixes_.end())
    throw std::runtime_error("the log holds no channel of prefix '" + *wanted_ + "' (it holds " +
                             quotedList(prefixes_, nullptr) + ")");
  if (prefixes_.size() < 2) return "";
  const std::string read = selected();
  return "this log holds " + std::to_string(prefixes_.size()) + " pipelines, by channel prefix: " +
         quotedList(prefixes_, &read) + "; choose one with --prefix P";
}

}  // namespace nerv

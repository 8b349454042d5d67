#include "pipeline_keys.hpp"

namespace nerv {

const std::vector<std::string>& serviceOnlyKeys(const std::string& service) {
  static const std::vector<std::string> matcher = {"shard",          "queue", "output_encoding", "publish_confidence",
                                                   "row_check_every_frames", "max_row_offset_px",
                                                   "row_correction", "row_correction_above_px",
                                                   "max_row_correction_px", "offset_correction",
                                                   "max_offset_correction_px", "rig_state_file",
                                                   "max_view_delay_ms", "max_disparity_offset_px"};
  static const std::vector<std::string> stixel = {"shard", "queue", "min_prior_confidence", "max_prior_age_frames",
                                                  "max_prior_age_ms", "max_unobserved_fraction"};
  static const std::vector<std::string> joining = {"shard", "queue", "join_capacity", "join_timeout_ms"};
  static const std::vector<std::string> none = {"shard"};
  if (service == "stereo_matcher") return matcher;
  if (service == "stixel") return stixel;
  if (service == "snv_extrinsic" || service == "validator") return joining;
  return none;
}

void allowServiceOnlyKeys(ConfigSection& section, const std::string& service) {
  for (const std::string& k : serviceOnlyKeys(service)) section.allow(k);
}

const std::vector<std::string>& pipelineTopLevelKeys() {
  static const std::vector<std::string> keys = {"lcm_url",  "channel_prefix", "limits",    "warmup", "stereo_matcher",
                                                "stixel",   "snv_extrinsic",  "validator", "source", "run"};
  return keys;
}

void allowPipelineTopLevelKeys(ConfigSection& root) {
  for (const std::string& k : pipelineTopLevelKeys()) root.allow(k);
}

}  // namespace nerv

#include "pipeline_keys.hpp"

namespace nerv {

const std::vector<std::string>& serviceOnlyKeys(const std::string& service) {
  static const std::vector<std::string> matcher = {"shard", "queue", "output_encoding", "publish_confidence"};
  static const std::vector<std::string> stixel = {"shard", "queue", "min_prior_confidence", "max_prior_age_frames",
                                                  "max_unobserved_fraction"};
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

}  // namespace nerv

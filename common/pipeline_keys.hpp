// The keys a service's config section may hold besides its algorithm's
// parameters: what the service's main reads (queue, join settings, output
// encoding, health limits) and `shard`, which ServiceConfig reads for every
// service. A tool that runs the algorithms in-process from a pipeline config
// (bench_detection, nerv_eval_disparity) allows them, so that the file the
// services run with is one the tool accepts (until 2026-12-05 bench_detection
// rejected config/pipeline.yaml for the stixel service's
// max_unobserved_fraction). A key added to a service's main belongs here too;
// every service's --check-config accepts every key listed (qualityServiceKeys.*).
#pragma once

#include <string>
#include <vector>

#include "config.hpp"

namespace nerv {

const std::vector<std::string>& serviceOnlyKeys(const std::string& service);
void allowServiceOnlyKeys(ConfigSection& section, const std::string& service);

// The top-level keys of a pipeline config: lcm_url, channel_prefix, limits,
// warmup, the four service sections, source and run. A tool allows them all and
// reads the ones it uses.
const std::vector<std::string>& pipelineTopLevelKeys();
void allowPipelineTopLevelKeys(ConfigSection& root);

}  // namespace nerv

// What every service's main does first: parse the command line, read the
// pipeline config, take the shared keys (bus, prefix, limits, shard) and hand
// the service its own section. Bad flags or keys end the program with one line.
//
//   <service> [--config FILE] [--instance NAME] [--lcm-url URL] [--prefix P] [--shard K/N]
//             [--check-config]   (validate the config and exit 0, or print the error and exit 2)
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "config.hpp"
#include "lcm_node.hpp"
#include "warmup_frame.hpp"

namespace nerv {

// Top-level keys of a pipeline config (besides the service sections).
// lcm_url, channel_prefix, limits {max_width, max_height}, warmup {width, height}, source, run.
class ServiceConfig {
 public:
  ServiceConfig(const std::string& service, int argc, char** argv);

  // The service's own section (`stixel:` ...). Declare keys, then call finish().
  ConfigSection& section() { return section_; }
  // Checks that no unknown key is left anywhere; throws ConfigError.
  // With --check-config, exits 0 here.
  void finish();
  NodeOptions nodeOptions() const { return options_; }
  // Top-level `warmup: {width, height}`: the frame size to warm up on at start
  // (warmup_frame.hpp); off when absent.
  WarmupSize warmup() const { return warmup_; }

 private:
  ConfigSection root_;
  ConfigSection section_;
  NodeOptions options_;
  WarmupSize warmup_;
  bool check_only_ = false;
};

// Runs body (the service's algorithm on warmup_frame.hpp's frames) when the
// config asks for a warm-up, and says on stderr how long it took:
// "stixel: warmed up on a 1242x375 frame in 18.2 ms".
void warmUp(const ServiceConfig& config, const std::function<void(const WarmupSize&)>& body);

// Settings of a service that joins two inputs by seq (see seq_join.hpp):
// queue (LCM queue per input), join_capacity, join_timeout_ms.
struct JoinSettings {
  int queue = 2;
  int capacity = 8;
  int64_t timeout_us = 2000000;
};
JoinSettings readJoinSettings(ConfigSection& section, int default_queue);

// Runs body(config) and turns configuration / start-up errors into one line on
// stderr ("stixel: unknown config key 'stixel.foo'") and exit code 2.
int runService(const std::string& service, int argc, char** argv,
               const std::function<int(ServiceConfig&)>& body);

}  // namespace nerv

#include "service_config.hpp"

#include "build_version.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace nerv {
namespace {

const char* const kSections[] = {"stereo_matcher", "stixel", "snv_extrinsic", "validator",
                                 "source", "run"};

struct Flags {
  std::string config, instance, lcm_url, prefix, shard;
  bool has_prefix = false;
  bool check_only = false;
  bool version = false;
};

Flags parseFlags(int argc, char** argv) {
  Flags f;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* name) {
      if (i + 1 >= argc) throw ConfigError(std::string("flag ") + name + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "--config") f.config = value("--config");
    else if (arg == "--instance") f.instance = value("--instance");
    else if (arg == "--lcm-url") f.lcm_url = value("--lcm-url");
    else if (arg == "--prefix") { f.prefix = value("--prefix"); f.has_prefix = true; }
    else if (arg == "--shard") f.shard = value("--shard");
    else if (arg == "--check-config") f.check_only = true;
    else if (arg == "--version") f.version = true;
    else
      throw ConfigError("unknown flag '" + arg +
                        "' (flags: --config FILE --instance NAME --lcm-url URL --prefix P "
                        "--shard K/N --check-config --version)");
  }
  return f;
}

YAML::Node rootNode(const std::string& path) {
  return path.empty() ? YAML::Node(YAML::NodeType::Map) : loadConfigFile(path);
}

}  // namespace

ServiceConfig::ServiceConfig(const std::string& service, int argc, char** argv)
    : root_(YAML::Node(), ""), section_(YAML::Node(), service) {
  const Flags flags = parseFlags(argc, argv);
  root_ = ConfigSection(rootNode(flags.config), "");
  options_.service = service;
  check_only_ = flags.check_only;
  root_.get("lcm_url", options_.lcm_url);
  root_.get("channel_prefix", options_.channel_prefix);
  ConfigSection limits = root_.section("limits");
  limits.get("max_width", options_.limits.max_width, 16, 16384);
  limits.get("max_height", options_.limits.max_height, 16, 16384);
  limits.finish();
  ConfigSection warmup = root_.section("warmup");
  warmup.get("width", warmup_.width, 0, 16384);
  warmup.get("height", warmup_.height, 0, 16384);
  warmup.finish();
  if ((warmup_.width > 0) != (warmup_.height > 0))
    throw ConfigError("warmup: width and height are both 0 (off) or both set, got " + std::to_string(warmup_.width) +
                      " x " + std::to_string(warmup_.height));
  if (warmup_.on() && (warmup_.width < 16 || warmup_.height < 16))
    throw ConfigError("warmup: " + std::to_string(warmup_.width) + " x " + std::to_string(warmup_.height) +
                      " is smaller than the smallest frame the limits allow (16 x 16)");
  if (warmup_.width > options_.limits.max_width || warmup_.height > options_.limits.max_height)
    throw ConfigError("warmup: " + std::to_string(warmup_.width) + " x " + std::to_string(warmup_.height) +
                      " is larger than the frames the limits accept (" + std::to_string(options_.limits.max_width) +
                      " x " + std::to_string(options_.limits.max_height) + ")");
  for (const char* name : kSections)
    if (service != name) root_.allow(name);
  section_ = root_.section(service);
  ConfigSection shard = section_.section("shard");
  shard.get("count", options_.shard_count, 1, 64);
  shard.get("index", options_.shard_index, 0, 63);
  shard.finish();
  if (!flags.instance.empty()) options_.instance = flags.instance;
  if (!flags.lcm_url.empty()) options_.lcm_url = flags.lcm_url;
  if (flags.has_prefix) options_.channel_prefix = flags.prefix;
  if (!flags.shard.empty()) {
    int k = -1, n = -1;
    char extra;
    if (std::sscanf(flags.shard.c_str(), "%d/%d%c", &k, &n, &extra) != 2)
      throw ConfigError("flag --shard '" + flags.shard + "' is not K/N");
    options_.shard_index = k;
    options_.shard_count = n;
  }
  if (options_.shard_count < 1 || options_.shard_index < 0 ||
      options_.shard_index >= options_.shard_count)
    throw ConfigError("shard " + std::to_string(options_.shard_index) + "/" +
                      std::to_string(options_.shard_count) + " is not within 0..count-1");
  if (options_.shard_count > 1 && flags.instance.empty())
    options_.instance = "shard" + std::to_string(options_.shard_index);
}

void ServiceConfig::finish() {
  section_.finish();
  root_.finish();
  if (check_only_) std::exit(0);  // --check-config: the config is valid, nothing else to do
}

void warmUp(const ServiceConfig& config, const std::function<void(const WarmupSize&)>& body) {
  const WarmupSize size = config.warmup();
  if (!size.on()) return;
  const auto start = std::chrono::steady_clock::now();
  body(size);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%s: warmed up on a %dx%d frame in %.1f ms\n", config.nodeOptions().service.c_str(), size.width,
               size.height, ms);
}

JoinSettings readJoinSettings(ConfigSection& section, int default_queue) {
  JoinSettings j;
  j.queue = default_queue;
  double timeout_ms = j.timeout_us / 1000.0;
  section.get("queue", j.queue, 1, 100);
  section.get("join_capacity", j.capacity, 1, 1000);
  section.get("join_timeout_ms", timeout_ms, 1, 60000);
  j.timeout_us = static_cast<int64_t>(timeout_ms * 1000);
  return j;
}

int runService(const std::string& service, int argc, char** argv,
               const std::function<int(ServiceConfig&)>& body) {
  try {
    if (parseFlags(argc, argv).version) {
      std::printf("%s: nerv %s\n", service.c_str(), buildVersion());
      return 0;
    }
    ServiceConfig config(service, argc, argv);
    return body(config);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "%s: %s\n", service.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", service.c_str(), e.what());
    return 2;
  }
}

}  // namespace nerv

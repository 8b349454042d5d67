#include "lcm_node.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "build_version.hpp"
#include "message_fingerprint.hpp"
#include "health_compat.hpp"
#include "nerv/health_t.hpp"

namespace nerv {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

std::string resolveUrl(const std::string& configured) {
  if (!configured.empty()) return configured;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env && *env) return env;
  return kDefaultLcmUrl;
}

float percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return static_cast<float>(v[k]);
}

}  // namespace

int64_t nowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string undecodableMessage(const std::string& channel, const char* type, int64_t hash, const void* data,
                               uint32_t size) {
  if (size < 8) return "message on " + channel + " does not decode as " + type + ": " + std::to_string(size) + " bytes";
  const int64_t fp = messageFingerprint(data, size);
  if (fp == hash)
    return "message on " + channel + " does not decode as " + type + ": its payload is broken";
  char line[400];
  std::snprintf(line, sizeof line,
                "message on %s does not decode as %s: its layout (fingerprint %016llx) is not this build's "
                "(%016llx): a process of another nerv build publishes it, or another program uses the channel "
                "(nerv status lists each process's build)",
                channel.c_str(), type, static_cast<unsigned long long>(fp), static_cast<unsigned long long>(hash));
  return line;
}

std::string hostName() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return host;
}

Node::Node(NodeOptions options) : options_(std::move(options)), lcm_(resolveUrl(options_.lcm_url)) {
  if (!lcm_.good())
    throw std::runtime_error("LCM cannot start on " + resolveUrl(options_.lcm_url) +
                             " (no multicast route? see README: network set-up)");
  if (options_.shard_count < 1 || options_.shard_index < 0 ||
      options_.shard_index >= options_.shard_count)
    throw std::runtime_error("shard index " + std::to_string(options_.shard_index) + " of " +
                             std::to_string(options_.shard_count) + " is invalid");
  host_ = hostName();
  lcm_.subscribe(channel("NERV_HEALTH"), &Node::onHealth, this)->setQueueCapacity(50);
  std::fprintf(stderr, "%s: nerv %s\n", options_.service.c_str(), buildVersion());
  // A shard sees every frame and takes one in shard_count: said at start, since a
  // `shard.count` set without the other shards running (or run.shards) loses the rest quietly.
  if (options_.shard_count > 1)
    std::fprintf(stderr, "%s: shard %d of %d (instance %s): takes the frames whose seq %% %d is %d; the other %d "
                 "shards must run for every frame to come out\n",
                 options_.service.c_str(), options_.shard_index, options_.shard_count, options_.instance.c_str(),
                 options_.shard_count, options_.shard_index, options_.shard_count - 1);
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

Node::~Node() = default;

bool Node::stopRequested() { return g_stop; }

bool Node::ownsFrame(int64_t seq) const {
  const int64_t n = options_.shard_count;
  return ((seq % n) + n) % n == options_.shard_index;
}

void Node::countOut(int64_t capture_utime, double processing_ms) {
  ++frames_out_;
  const double latency_ms = (nowUtime() - capture_utime) / 1000.0;
  // Out before it was captured: the capture host's clock is ahead of this one (computers
  // without clock synchronisation). Such a latency means nothing: counted, not averaged.
  if (latency_ms < 0)
    count("clock_skew_frames");
  else
    latencies_ms_.push_back(latency_ms);
  processing_ms_.push_back(processing_ms);
}

void Node::error(const std::string& counter, const std::string& message) {
  ++errors_;
  ++counters_[counter];
  last_error_ = counter + ": " + message;
  const int64_t now = nowUtime();
  // At most 20 lines a second, so a flood of bad input cannot flood the log.
  if (now - error_window_start_utime_ > 1000000) {
    error_window_start_utime_ = now;
    error_lines_in_window_ = 0;
  }
  if (error_lines_in_window_++ < 20) {
    if (suppressed_errors_ > 0)
      std::fprintf(stderr, "%s: (%d similar errors not shown)\n", options_.service.c_str(),
                   suppressed_errors_);
    std::fprintf(stderr, "%s: %s\n", options_.service.c_str(), last_error_.c_str());
    last_error_print_utime_ = now;
    suppressed_errors_ = 0;
  } else {
    ++suppressed_errors_;
  }
}

int64_t Node::counter(const std::string& name) const {
  auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

void Node::noteSeq(const std::string& channel, int64_t seq) {
  const int64_t lost = seq_gaps_[channel].note(seq);
  if (lost > 0) {
    countDropped(lost);
    count("lost_" + channel, lost);
  }
}

void Node::onHealth(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  health_t h;  // any layout: a process of an older build is still heard (health_compat.hpp)
  if (!decodeHealth(rbuf->data, static_cast<int>(rbuf->data_size), h)) return;
  for (auto& handler : health_handlers_) guarded([&] { handler(h); });
  if (h.host == host_ && h.pid == static_cast<int32_t>(getpid())) return;  // this process
  if (auto it = peer_started_.find(h.service); it != peer_started_.end()) {
    // At most kMaxPeersHeard remembered: a bus of restarting processes must not grow it for ever
    // (forgetting one only calls its handlers once more).
    constexpr size_t kMaxPeersHeard = 4096;
    if (peers_heard_.size() >= kMaxPeersHeard) peers_heard_.clear();
    if (peers_heard_.insert(h.service + " " + h.host + " " + std::to_string(h.pid)).second)
      for (auto& handler : it->second) guarded([&] { handler(h.host, h.pid); });
  }
  if (h.service != options_.service || h.instance != options_.instance) return;
  if (!twins_.insert(h.host + " " + std::to_string(h.pid)).second) return;
  error("duplicate_instance", "another " + h.service + "/" + h.instance + " runs on host " + h.host +
                                  ", pid " + std::to_string(h.pid) +
                                  ": each of its frames is processed twice (stop one, or give them other "
                                  "--shard or --prefix)");
}

void Node::guarded(const std::function<void()>& body) {
  try {
    body();
  } catch (const std::exception& e) {
    error("processing_failed", e.what());
  } catch (...) {
    error("processing_failed", "unknown exception");
  }
}

void addProcessGauges(health_t& h, CpuShare& cpu_share) {
  const ProcessUsage usage = readProcessUsage();
  const std::pair<const char*, double> process_gauges[] = {
      {"cpu_percent", cpu_share.percentSince(usage.cpu_s, h.utime)},
      {"rss_mb", usage.rss_mb},
      {"rss_peak_mb", usage.rss_peak_mb}};
  for (const auto& [name, value] : process_gauges) {
    if (std::find(h.gauge_names.begin(), h.gauge_names.end(), name) != h.gauge_names.end())
      continue;  // a service's own gauge of that name wins
    h.gauge_names.push_back(name);
    h.gauge_values.push_back(value);
  }
  h.num_gauges = static_cast<int32_t>(h.gauge_names.size());
}

void Node::publishHealth() {
  health_t h{};  // every count zero until set: lcm-gen's structs leave them uninitialised
  h.utime = nowUtime();
  h.service = options_.service;
  h.instance = options_.instance;
  h.host = host_;
  h.pid = static_cast<int32_t>(getpid());
  h.frames_in = frames_in_;
  h.frames_out = frames_out_;
  h.frames_dropped = frames_dropped_;
  h.errors = errors_;
  for (const auto& [name, value] : counters_) {
    h.counter_names.push_back(name);
    h.counter_values.push_back(value);
  }
  h.num_counters = static_cast<int32_t>(h.counter_names.size());
  for (const auto& [name, value] : gauges_) {
    h.gauge_names.push_back(name);
    h.gauge_values.push_back(value);
  }
  addProcessGauges(h, cpu_share_);
  h.latency_p50_ms = percentile(latencies_ms_, 0.5);
  h.latency_p95_ms = percentile(latencies_ms_, 0.95);
  double sum = 0;
  for (double v : processing_ms_) sum += v;
  h.processing_ms = processing_ms_.empty() ? 0.f : static_cast<float>(sum / processing_ms_.size());
  // degraded: errors since the last report; idle: nothing published since then.
  h.status = errors_ > errors_at_last_health_ ? "degraded" : (processing_ms_.empty() ? "idle" : "ok");
  errors_at_last_health_ = errors_;
  h.last_error = last_error_;
  h.version = buildVersion();
  latencies_ms_.clear();
  processing_ms_.clear();
  lcm_.publish(channel("NERV_HEALTH"), &h);
  last_health_utime_ = h.utime;
}

void Node::poll(int timeout_ms) {
  if (last_health_utime_ == 0) publishHealth();
  if (lcm_.handleTimeout(timeout_ms) < 0 && !g_stop) {  // a signal interrupting select is no error
    error("lcm_failed", "handleTimeout failed");
    usleep(10000);  // a broken socket must not spin the CPU
  }
  for (auto& tick : ticks_) guarded(tick);
  if (nowUtime() - last_health_utime_ >= options_.health_period_s * 1e6) publishHealth();
}

int Node::spin() {
  while (!g_stop) poll(50);
  publishHealth();
  return 0;
}

}  // namespace nerv

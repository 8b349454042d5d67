// The LCM side of every nerv service: subscriptions that decode and validate,
// publishing, counters, health once a second, and a clean exit on SIGINT/SIGTERM.
// Handlers never throw into LCM's C stack: exceptions become counted errors.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "message_check.hpp"
#include "process_usage.hpp"
#include "nerv/health_t.hpp"
#include "seq_gap_tracker.hpp"

namespace nerv {

template <class T, class = void>
struct HasFrameHeader : std::false_type {};
template <class T>
struct HasFrameHeader<T, std::void_t<decltype(std::declval<T>().header.seq)>> : std::true_type {};

// Default bus: stays on this host (ttl=0) with a receive buffer for full frames.
constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

struct NodeOptions {
  std::string service;          // e.g. "stixel"
  std::string instance = "0";   // distinguishes shards / copies
  std::string lcm_url;          // empty: LCM_DEFAULT_URL or kDefaultLcmUrl
  std::string channel_prefix;   // prepended to every channel, e.g. "FRONT_"
  Limits limits;
  int shard_index = 0;          // this instance handles frames with seq % shard_count == shard_index
  int shard_count = 1;
  double health_period_s = 1.0;
};

int64_t nowUtime();
// The line for a message on `channel` that does not decode as `type`: a fingerprint other than
// the type's (`hash`) is another layout of it, from a process of another build (a computer of
// the vehicle not yet updated) or another program on the channel, and is named as such;
// otherwise the payload is broken.
std::string undecodableMessage(const std::string& channel, const char* type, int64_t hash, const void* data,
                               uint32_t size);
// Appends the process's cpu_percent (share since cpu_share's last call), rss_mb and rss_peak_mb
// to a report's gauges and sets num_gauges; a gauge of the same name already there stays.
void addProcessGauges(health_t& h, CpuShare& cpu_share);
// This computer's name, as every NERV_HEALTH report carries it.
std::string hostName();

class Node {
 public:
  explicit Node(NodeOptions options);  // throws std::runtime_error when LCM cannot start
  ~Node();

  std::string channel(const std::string& base) const { return options_.channel_prefix + base; }
  const NodeOptions& options() const { return options_; }
  bool ownsFrame(int64_t seq) const;

  // Decodes each message as T and calls handler; failed decodes are counted as
  // "decode_failed". queue_capacity bounds LCM's queue (older messages dropped).
  template <class T>
  void subscribe(const std::string& base_channel, std::function<void(const T&)> handler,
                 int queue_capacity = 2);

  // Encodes into a buffer kept across calls: LCM's own publish(&msg) allocates a
  // fresh one per message, and for a 1.4 MB DISPARITY that allocation (mmap, page
  // faults, munmap with a TLB shootdown on a VM) cost more than sending it
  // (docs/stereo.md "Publishing a frame").
  template <class T>
  void publish(const std::string& base_channel, const T& msg) {
    const int size = msg.getEncodedSize();
    if (static_cast<size_t>(size) > publish_buffer_.size()) publish_buffer_.resize(size);
    if (msg.encode(publish_buffer_.data(), 0, size) < 0) {
      error("encode_failed", "a " + std::string(T::getTypeName()) + " for " + channel(base_channel) + " does not encode");
      return;
    }
    lcm_.publish(channel(base_channel), publish_buffer_.data(), static_cast<unsigned>(size));
  }

  // Counters reported in health.
  void countIn() { ++frames_in_; }
  void countDropped(int64_t n = 1) { frames_dropped_ += n; }
  // After publishing an output derived from a frame captured at capture_utime.
  void countOut(int64_t capture_utime, double processing_ms);
  // A rejected message or failed step: one line on stderr (rate-limited) and a counter.
  void error(const std::string& counter, const std::string& message);
  // A named event that is not an error (shown among the health counters).
  void count(const std::string& counter, int64_t n = 1) { counters_[counter] += n; }
  // The latest value of a measured quantity (the unit in its name), in every health report
  // from now on: e.g. the rig's row offset, so that a dashboard plots it before it is an error.
  // Every report also carries the process's cpu_percent, rss_mb and rss_peak_mb.
  void gauge(const std::string& name, double value) { gauges_[name] = value; }
  int64_t counter(const std::string& name) const;
  int64_t framesIn() const { return frames_in_; }
  int64_t framesOut() const { return frames_out_; }
  int64_t errors() const { return errors_; }

  // Called every loop iteration (about every 50 ms) for timeouts.
  void onTick(std::function<void()> tick) { ticks_.push_back(std::move(tick)); }
  // Called with the host and pid of each process of `service` (any instance) the first time its
  // NERV_HEALTH is heard: a stage that just started or restarted announces itself before its
  // first output (its first report goes out at its first poll), so a partner can expect it again.
  void onPeerStarted(const std::string& service, std::function<void(const std::string& host, int pid)> handler) {
    peer_started_[service].push_back(std::move(handler));
  }
  // Called with every NERV_HEALTH report on the bus, this process's own included, in any layout
  // nerv has published (health_compat.hpp: older builds' reports have the newer fields empty).
  // Subscribing to NERV_HEALTH as a health_t would count older builds' reports as decode_failed.
  void onHealthReport(std::function<void(const health_t&)> handler) { health_handlers_.push_back(std::move(handler)); }

  // Handles messages for up to timeout_ms, runs the ticks, publishes health when due.
  void poll(int timeout_ms);
  // poll() until SIGINT/SIGTERM; returns the exit code (0).
  int spin();
  static bool stopRequested();
  // Publishes a health report now (spin() does so on exit by itself).
  void reportHealth() { publishHealth(); }

 private:
  struct Subscription {
    Node* node;
    std::function<void(const lcm::ReceiveBuffer*, const std::string&)> on_message;
    void handle(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      on_message(rbuf, channel);
    }
  };
  void guarded(const std::function<void()>& body);
  // Frames missing from a channel's seq sequence were lost on the way (UDP
  // buffer overrun, LCM queue full); they are counted as dropped once overdue
  // (seq_gap_tracker.hpp: shards publish out of order).
  void noteSeq(const std::string& channel, int64_t seq);
  std::map<std::string, SeqGapTracker> seq_gaps_;
  void publishHealth();
  // Another process reporting this service and instance on the bus (a stage started
  // by hand beside a supervisor's, a second supervisor): every frame it owns is then
  // processed and published twice. One error per such process.
  void onHealth(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  std::set<std::string> twins_;  // "host pid" of each one seen
  std::map<std::string, std::vector<std::function<void(const std::string&, int)>>> peer_started_;
  std::set<std::string> peers_heard_;  // "service host pid" of each peer process heard
  std::vector<std::function<void(const health_t&)>> health_handlers_;

  NodeOptions options_;
  lcm::LCM lcm_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  std::vector<uint8_t> publish_buffer_;  // publish()'s encoding, reused
  std::vector<std::function<void()>> ticks_;
  int64_t frames_in_ = 0, frames_out_ = 0, frames_dropped_ = 0, errors_ = 0;
  std::map<std::string, int64_t> counters_;
  std::map<std::string, double> gauges_;
  CpuShare cpu_share_;  // cpu_percent in each report: the share since the report before
  std::vector<double> latencies_ms_;   // since the last health report
  std::vector<double> processing_ms_;  // since the last health report
  std::string last_error_;
  int64_t last_health_utime_ = 0;
  int64_t errors_at_last_health_ = 0;
  int64_t last_error_print_utime_ = 0;
  int64_t error_window_start_utime_ = 0;
  int error_lines_in_window_ = 0;
  int suppressed_errors_ = 0;
  std::string host_;
};

template <class T>
void Node::subscribe(const std::string& base_channel, std::function<void(const T&)> handler,
                     int queue_capacity) {
  auto sub = std::make_unique<Subscription>();
  sub->node = this;
  // One message object per subscription, decoded into again and again: its arrays
  // keep their capacity, so a 1.4 MB DISPARITY is not allocated anew per frame
  // (handlers get a const reference and copy what they keep).
  auto kept = std::make_shared<T>();
  sub->on_message = [this, handler, kept](const lcm::ReceiveBuffer* rbuf, const std::string& ch) {
    T& msg = *kept;
    // Generated decoders return < 0 on a wrong fingerprint, a short buffer or an
    // array count longer than the buffer (cmake/LcmDecoderBounds.cmake: before
    // that, a corrupt count allocated gigabytes or threw from std::vector). A
    // throw is still a rejection.
    bool decoded = false;
    try {
      decoded = msg.decode(rbuf->data, 0, rbuf->data_size) >= 0;
    } catch (const std::exception&) {
    }
    if (!decoded) {
      error("decode_failed", undecodableMessage(ch, T::getTypeName(), T::getHash(), rbuf->data, rbuf->data_size));
      return;
    }
    if constexpr (HasFrameHeader<T>::value) noteSeq(ch, msg.header.seq);
    guarded([&] { handler(msg); });
  };
  lcm::Subscription* s =
      lcm_.subscribe(channel(base_channel), &Subscription::handle, sub.get());
  if (s && queue_capacity > 0) s->setQueueCapacity(queue_capacity);
  subscriptions_.push_back(std::move(sub));
}

}  // namespace nerv

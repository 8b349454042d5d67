// The node helper's health report, on LCM's in-process bus (memq://): latencies and
// the frames whose capture time lies in this computer's future (unsynchronised clocks).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "lcm_node.hpp"
#include "process_usage.hpp"
#include "nerv/health_t.hpp"
#include "nerv/health_v1_t.hpp"

using namespace nerv;

namespace {

health_t reportOnce(Node& node) {
  std::optional<health_t> got;
  node.subscribe<health_t>("NERV_HEALTH", [&](const health_t& h) { got = h; }, 4);
  node.reportHealth();
  for (int i = 0; i < 20 && !got; ++i) node.poll(50);
  EXPECT_TRUE(got.has_value()) << "no NERV_HEALTH on memq://";
  return got.value_or(health_t{});
}

int64_t counterOf(const health_t& h, const std::string& name) {
  for (int i = 0; i < h.num_counters; ++i)
    if (h.counter_names[i] == name) return h.counter_values[i];
  return 0;
}

// A report in the first layout of health_t (another fingerprint than this build's).
health_v1_t health_v1_like() {
  health_v1_t h{};
  h.service = "stixel";
  h.num_counters = 0;
  return h;
}

NodeOptions memq() {
  NodeOptions o;
  o.service = "test";
  o.lcm_url = "memq://";
  o.health_period_s = 1000;  // only the report the test asks for
  return o;
}

}  // namespace

TEST(commonNodeHealth, FramesFromTheFutureAreCountedNotAveraged) {
  Node node(memq());
  node.countOut(nowUtime() - 20'000, 1.0);     // captured 20 ms ago
  node.countOut(nowUtime() + 5'000'000, 1.0);  // "captured" in 5 s: the capture host's clock is ahead
  const health_t h = reportOnce(node);
  EXPECT_EQ(h.frames_out, 2);
  EXPECT_EQ(counterOf(h, "clock_skew_frames"), 1);
  EXPECT_GE(h.latency_p95_ms, 20.0f);
  EXPECT_LT(h.latency_p95_ms, 1000.0f) << "the skewed frame must not enter the latency";
  EXPECT_EQ(h.status, "ok");
}

TEST(commonNodeHealth, OnlySkewedFramesStillCountAsWorking) {
  Node node(memq());
  node.countOut(nowUtime() + 5'000'000, 1.0);
  const health_t h = reportOnce(node);
  EXPECT_EQ(counterOf(h, "clock_skew_frames"), 1);
  EXPECT_EQ(h.status, "ok") << "frames went out: not idle";
}

// The service's own gauges first (by name), then the process's (process_usage.hpp).
const std::vector<std::string> kProcessGauges = {"cpu_percent", "rss_mb", "rss_peak_mb"};

TEST(commonNodeHealth, GaugesCarryTheirLatestValue) {
  Node node(memq());
  EXPECT_EQ(reportOnce(node).gauge_names, kProcessGauges) << "only the process's own gauges";
  node.gauge("row_offset_px", 0.12);
  node.gauge("view_delay_ms", -0.5);
  node.gauge("row_offset_px", 0.93);  // the latest value replaces the one before
  const health_t h = reportOnce(node);
  ASSERT_EQ(h.num_gauges, 5);
  ASSERT_EQ(h.gauge_names.size(), 5u);
  EXPECT_EQ(h.gauge_names[0], "row_offset_px");
  EXPECT_DOUBLE_EQ(h.gauge_values[0], 0.93);
  EXPECT_EQ(h.gauge_names[1], "view_delay_ms");
  EXPECT_DOUBLE_EQ(h.gauge_values[1], -0.5);
  EXPECT_EQ(std::vector<std::string>(h.gauge_names.begin() + 2, h.gauge_names.end()), kProcessGauges);
  EXPECT_EQ(reportOnce(node).num_gauges, 5) << "a gauge stays in every report";
}

double gaugeOf(const health_t& h, const std::string& name) {
  for (int i = 0; i < h.num_gauges; ++i)
    if (h.gauge_names[i] == name) return h.gauge_values[i];
  ADD_FAILURE() << "no gauge " << name;
  return -1;
}

// Memory and CPU of the process in every report: a test of this size holds tens of MiB (the
// LCM library, gtest, its heap), and a report after a busy spell shows the CPU it took.
TEST(commonNodeHealth, EveryReportCarriesTheProcesssMemoryAndCpu) {
  Node node(memq());
  reportOnce(node);
  // Keep one core busy for 0.3 s of CPU time, then report: the share over that interval is
  // well above zero whatever the machine's load (the interval counts CPU time, not wall time).
  const ProcessUsage before = readProcessUsage();
  volatile double sink = 0;
  while (readProcessUsage().cpu_s - before.cpu_s < 0.3)
    for (int i = 0; i < 100000; ++i) sink = sink + i * 1e-9;
  const health_t h = reportOnce(node);
  EXPECT_GT(gaugeOf(h, "cpu_percent"), 5.0);
  EXPECT_LE(gaugeOf(h, "cpu_percent"), 100.0 * 64) << "more than 64 cores' worth";
  EXPECT_GT(gaugeOf(h, "rss_mb"), 1.0);
  EXPECT_GE(gaugeOf(h, "rss_peak_mb"), gaugeOf(h, "rss_mb") - 0.01);
}

TEST(commonNodeHealth, AServicesOwnGaugeOfAProcessNameWins) {
  Node node(memq());
  node.gauge("rss_mb", 12.5);
  const health_t h = reportOnce(node);
  EXPECT_EQ(std::count(h.gauge_names.begin(), h.gauge_names.end(), "rss_mb"), 1);
  EXPECT_DOUBLE_EQ(gaugeOf(h, "rss_mb"), 12.5);
}

// A stage that starts announces itself through its first NERV_HEALTH: the validator and
// snv_extrinsic wait for its messages again from then on (partner_join.hpp).
TEST(commonNodeHealth, APeerProcessIsAnnouncedOnceWhenFirstHeard) {
  Node node(memq());
  std::vector<std::string> started;
  node.onPeerStarted("snv_extrinsic", [&](const std::string& host, int pid) {
    started.push_back(host + " " + std::to_string(pid));
  });
  auto announce = [&](const std::string& service, const std::string& instance, int pid) {
    health_t h{};
    h.service = service;
    h.instance = instance;
    h.host = "car-pc-2";
    h.pid = pid;
    node.publish("NERV_HEALTH", h);
    for (int i = 0; i < 3; ++i) node.poll(20);
  };
  announce("snv_extrinsic", "0", 4711);
  announce("snv_extrinsic", "0", 4711);  // its next report: the same process
  announce("stixel", "0", 4712);         // another service
  announce("snv_extrinsic", "1", 4713);  // a second shard
  announce("snv_extrinsic", "0", 5000);  // the first one restarted
  node.reportHealth();                   // this process ("test") is no peer of itself
  for (int i = 0; i < 3; ++i) node.poll(20);
  EXPECT_EQ(started, std::vector<std::string>({"car-pc-2 4711", "car-pc-2 4713", "car-pc-2 5000"}));
}

// A message that does not decode is told apart: another layout of the type (a process of another
// build on the bus) or a broken payload. Both are counted as decode_failed.
TEST(commonNodeHealth, AnotherLayoutIsNamedAsAnotherBuild) {
  const uint8_t other[12] = {0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc, 0xde, 0xf0, 0, 0, 0, 0};
  const std::string line = undecodableMessage("STIXELS", "stixels_t", 0x0102030405060708LL, other, sizeof other);
  EXPECT_NE(line.find("message on STIXELS does not decode as stixels_t: its layout (fingerprint 123456789abcdef0) "
                      "is not this build's (0102030405060708): a process of another nerv build publishes it"),
            std::string::npos)
      << line;
  const uint8_t same[12] = {1, 2, 3, 4, 5, 6, 7, 8, 0xff, 0xff, 0xff, 0xff};
  EXPECT_EQ(undecodableMessage("STIXELS", "stixels_t", 0x0102030405060708LL, same, sizeof same),
            "message on STIXELS does not decode as stixels_t: its payload is broken");
  EXPECT_EQ(undecodableMessage("STIXELS", "stixels_t", 1, same, 5), "message on STIXELS does not decode as stixels_t: 5 bytes");

  Node node(memq());  // through a subscription: the counter and the report's last error
  node.subscribe<health_t>("OTHER", [](const health_t&) {}, 4);
  node.publish("OTHER", health_v1_like());
  for (int i = 0; i < 3; ++i) node.poll(20);
  EXPECT_EQ(node.counter("decode_failed"), 1);
  EXPECT_NE(reportOnce(node).last_error.find("its layout (fingerprint"), std::string::npos);
}

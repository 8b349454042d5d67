// NERV_HEALTH in every layout nerv has published (common/health_compat.hpp): the current one, the
// one before the gauges (health_v2_t) and the first (health_v1_t) decode into a health_t, the
// fields they lack empty; anything else is refused. Through the node helper, a process of an
// older build is heard like any other, and `nerv export --json` writes its reports.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "health_compat.hpp"
#include "json_writer.hpp"
#include "lcm_node.hpp"
#include "message_json.hpp"
#include "nerv/health_t.hpp"
#include "nerv/health_v1_t.hpp"
#include "nerv/health_v2_t.hpp"

namespace nerv {
namespace {

template <class T>
T filled() {
  T h{};
  h.utime = 1700000000000000;
  h.service = "snv_extrinsic";
  h.instance = "0";
  h.host = "car-pc-2";
  h.pid = 4711;
  h.frames_in = 30;
  h.frames_out = 29;
  h.frames_dropped = 1;
  h.errors = 2;
  h.counter_names = {"bad_size", "late_stixels"};
  h.counter_values = {1, 3};
  h.num_counters = 2;
  h.latency_p50_ms = 12.5f;
  h.latency_p95_ms = 20.0f;
  h.processing_ms = 2.5f;
  h.status = "degraded";
  h.last_error = "bad_size: frame 3: ...";
  return h;
}

template <class T>
std::vector<uint8_t> encoded(const T& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  EXPECT_GT(m.encode(buf.data(), 0, static_cast<int>(buf.size())), 0);
  return buf;
}

void expectCommonFields(const health_t& h) {
  EXPECT_EQ(h.utime, 1700000000000000);
  EXPECT_EQ(h.service, "snv_extrinsic");
  EXPECT_EQ(h.host, "car-pc-2");
  EXPECT_EQ(h.pid, 4711);
  EXPECT_EQ(h.frames_in, 30);
  EXPECT_EQ(h.frames_out, 29);
  EXPECT_EQ(h.frames_dropped, 1);
  EXPECT_EQ(h.errors, 2);
  ASSERT_EQ(h.num_counters, 2);
  EXPECT_EQ(h.counter_names, (std::vector<std::string>{"bad_size", "late_stixels"}));
  EXPECT_EQ(h.counter_values, (std::vector<int64_t>{1, 3}));
  EXPECT_FLOAT_EQ(h.latency_p95_ms, 20.0f);
  EXPECT_EQ(h.status, "degraded");
  EXPECT_EQ(h.last_error, "bad_size: frame 3: ...");
}

TEST(commonHealthCompat, EveryPublishedLayoutDecodes) {
  health_t now = filled<health_t>();
  now.version = "0.1.0 (acd9333)";
  now.gauge_names = {"row_offset_px"};
  now.gauge_values = {0.1};
  now.num_gauges = 1;
  health_v2_t before_gauges = filled<health_v2_t>();
  before_gauges.version = "0.1.0 (d149867)";
  const health_v1_t first = filled<health_v1_t>();
  ASSERT_NE(health_t::getHash(), health_v2_t::getHash());
  ASSERT_NE(health_v2_t::getHash(), health_v1_t::getHash());

  health_t h;
  HealthLayout layout = HealthLayout::Unknown;
  std::vector<uint8_t> buf = encoded(now);
  ASSERT_TRUE(decodeHealth(buf.data(), static_cast<int>(buf.size()), h, &layout));
  EXPECT_EQ(layout, HealthLayout::Current);
  expectCommonFields(h);
  ASSERT_EQ(h.num_gauges, 1);
  EXPECT_EQ(h.version, "0.1.0 (acd9333)");

  buf = encoded(before_gauges);
  ASSERT_TRUE(decodeHealth(buf.data(), static_cast<int>(buf.size()), h, &layout));
  EXPECT_EQ(layout, HealthLayout::WithoutGauges);
  expectCommonFields(h);
  EXPECT_EQ(h.num_gauges, 0);
  EXPECT_TRUE(h.gauge_names.empty());
  EXPECT_EQ(h.version, "0.1.0 (d149867)");

  buf = encoded(first);
  ASSERT_TRUE(decodeHealth(buf.data(), static_cast<int>(buf.size()), h, &layout));
  EXPECT_EQ(layout, HealthLayout::WithoutVersion);
  expectCommonFields(h);
  EXPECT_EQ(h.num_gauges, 0);
  EXPECT_EQ(h.version, kVersionUnknown);
}

TEST(commonHealthCompat, OtherOrBrokenPayloadsAreRefused) {
  health_t h;
  HealthLayout layout = HealthLayout::Current;
  std::vector<uint8_t> buf = encoded(filled<health_v1_t>());
  EXPECT_FALSE(decodeHealth(buf.data(), 7, h, &layout)) << "shorter than a fingerprint";
  EXPECT_EQ(layout, HealthLayout::Unknown);
  EXPECT_FALSE(decodeHealth(buf.data(), static_cast<int>(buf.size()) - 5, h)) << "cut short";
  EXPECT_FALSE(decodeHealth(nullptr, 0, h));
  std::vector<uint8_t> other = buf;
  other[3] ^= 0x40;  // a fingerprint of no layout
  EXPECT_FALSE(decodeHealth(other.data(), static_cast<int>(other.size()), h));
  // A counter count far beyond the payload (its int32 follows the errors field).
  health_v1_t big = filled<health_v1_t>();
  big.num_counters = 0;
  big.counter_names.clear();
  big.counter_values.clear();
  std::vector<uint8_t> b = encoded(big);
  const size_t count_at = b.size() - (4 + 4 + 4) - (4 + big.status.size() + 1) - (4 + big.last_error.size() + 1) - 4;
  b[count_at] = 0x7f;  // the count's high byte: about 2 billion entries
  EXPECT_FALSE(decodeHealth(b.data(), static_cast<int>(b.size()), h));
}

TEST(commonHealthCompat, AnOlderBuildOnTheBusIsHeard) {
  NodeOptions o;
  o.service = "validator";
  o.lcm_url = "memq://";
  o.health_period_s = 1000;
  Node node(o);
  std::vector<std::string> started, reports;
  node.onPeerStarted("snv_extrinsic", [&](const std::string& host, int pid) {
    started.push_back(host + " " + std::to_string(pid));
  });
  node.onHealthReport([&](const health_t& h) {  // its own report too, at its first poll
    if (h.service != "validator") reports.push_back(h.service + " " + h.version);
  });
  node.publish("NERV_HEALTH", filled<health_v1_t>());
  for (int i = 0; i < 3; ++i) node.poll(20);
  EXPECT_EQ(started, std::vector<std::string>({"car-pc-2 4711"}));
  EXPECT_EQ(reports, std::vector<std::string>({std::string("snv_extrinsic ") + kVersionUnknown}));
  EXPECT_EQ(node.counter("decode_failed"), 0);
}

TEST(commonHealthCompat, OlderReportsExportAsJson) {
  health_v2_t m = filled<health_v2_t>();
  m.version = "0.1.0 (d149867)";
  const std::vector<uint8_t> buf = encoded(m);
  JsonWriter j;
  EXPECT_EQ(writeMessageJson(buf.data(), static_cast<int>(buf.size()), j), "nerv.health_v2_t");
  const std::string s = j.str();
  EXPECT_NE(s.find(R"("service":"snv_extrinsic")"), std::string::npos) << s;
  EXPECT_NE(s.find(R"x("version":"0.1.0 (d149867)")x"), std::string::npos) << s;
  EXPECT_NE(s.find(R"("num_gauges":0)"), std::string::npos) << s;
}

}  // namespace
}  // namespace nerv

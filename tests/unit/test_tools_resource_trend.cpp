// ResourceTrend: each process's memory and CPU over a run, from hand-made health reports.
#include <gtest/gtest.h>

#include "json_writer.hpp"
#include "resource_trend.hpp"

using namespace nerv;

namespace {

health_t report(const std::string& service, int pid, double t_s, double rss_mb, double cpu_percent) {
  health_t h{};
  h.service = service;
  h.instance = "0";
  h.pid = pid;
  h.utime = 1'700'000'000'000'000LL + static_cast<int64_t>(t_s * 1e6);
  h.gauge_names = {"cpu_percent", "row_offset_px", "rss_mb", "rss_peak_mb"};
  h.gauge_values = {cpu_percent, 0.1, rss_mb, rss_mb};
  h.num_gauges = 4;
  return h;
}

}  // namespace

TEST(toolsResourceTrend, MemoryFirstLastPeakAndGrowthAfterTheFirstMinute) {
  ResourceTrend trend;
  trend.add(report("stixel", 10, 0, 40, 900));  // first report: its share covers the warm-up
  for (int s = 1; s <= 3600; ++s) trend.add(report("stixel", 10, s, s < 60 ? 40 + s * 0.1 : 46 + (s - 60) / 600.0, 8));
  const auto& p = trend.processes().at("stixel/0");
  EXPECT_EQ(p.reports(), 3601);
  EXPECT_DOUBLE_EQ(p.rssFirstMb(), 40);
  EXPECT_DOUBLE_EQ(p.rssSettledMb(), 46);
  EXPECT_DOUBLE_EQ(p.rssLastMb(), 46 + 3540 / 600.0);
  EXPECT_DOUBLE_EQ(p.rssMaxMb(), p.rssLastMb());
  EXPECT_NEAR(p.growthMbPerHour(), 6.0, 1e-9) << "0.1 MiB a minute after the first";
  EXPECT_NE(trend.text().find("+6.0 MiB/h over the second half"), std::string::npos) << trend.text();
  EXPECT_DOUBLE_EQ(p.cpuMean(), 8) << "the first report's share (the warm-up) is left out";
  EXPECT_DOUBLE_EQ(p.cpu_max, 8);
}

// An allocator that takes one more step after the first minute has not leaked: the growth is
// measured over the second half, where the memory is flat again.
TEST(toolsResourceTrend, OneStepAfterTheFirstMinuteIsNotGrowth) {
  ResourceTrend trend;
  for (int s = 0; s <= 900; ++s) trend.add(report("stereo_matcher", 7, s, s < 60 ? 90 : s < 240 ? 97.5 : 98.4, 60));
  const auto& p = trend.processes().at("stereo_matcher/0");
  EXPECT_DOUBLE_EQ(p.rssSettledMb(), 97.5);
  EXPECT_DOUBLE_EQ(p.growthMbPerHour(), 0);
}

TEST(toolsResourceTrend, AShortRunHasNoGrowthFigure) {
  ResourceTrend trend;
  for (int s = 0; s < 100; ++s) trend.add(report("validator", 11, s, 20 + s, 3));
  const auto& p = trend.processes().at("validator/0");
  EXPECT_NE(p.settled(), nullptr);
  EXPECT_DOUBLE_EQ(p.growthMbPerHour(), 0) << "40 s after the first minute say nothing about a leak";
  EXPECT_EQ(trend.text().find("MiB/h"), std::string::npos);
}

TEST(toolsResourceTrend, ARestartedProcessIsFollowedFromItsNewPid) {
  ResourceTrend trend;
  trend.add(report("stereo_matcher", 20, 0, 80, 50));
  trend.add(report("stereo_matcher", 20, 1, 300, 50));
  trend.add(report("stereo_matcher", 21, 2, 70, 400));
  trend.add(report("stereo_matcher", 21, 3, 75, 60));
  const auto& p = trend.processes().at("stereo_matcher/0");
  EXPECT_EQ(p.pid, 21);
  EXPECT_EQ(p.restarts, 1);
  EXPECT_EQ(p.reports(), 2);
  EXPECT_DOUBLE_EQ(p.rssFirstMb(), 70);
  EXPECT_DOUBLE_EQ(p.rssMaxMb(), 75) << "the old process's peak is not the new one's";
  EXPECT_DOUBLE_EQ(p.cpuMean(), 60);
  EXPECT_NE(trend.text().find("figures of pid 21, after 1 earlier process"), std::string::npos) << trend.text();
}

TEST(toolsResourceTrend, ReportsWithoutTheGaugesAreSkipped) {
  ResourceTrend trend;
  health_t old{};
  old.service = "stixel";
  old.instance = "0";
  old.pid = 5;
  trend.add(old);  // an older build's report: no rss_mb
  EXPECT_TRUE(trend.processes().empty());
  JsonWriter j(false);
  j.beginObject();
  trend.writeJson(j);
  j.endObject();
  EXPECT_EQ(j.str(), R"({"resources":{}})");
}

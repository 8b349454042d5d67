// Memory and CPU of each process over a recorded run, from its NERV_HEALTH gauges (rss_mb,
// cpu_percent; common/process_usage.hpp): whether a stage's memory grows over a long drive, and
// what share of the computer's cores it takes. A process that restarted is followed from its
// new pid on (the restarts are counted; so is a short-lived probe of the same name, such as the
// nerv_source that `nerv run` starts to see the logger record).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "nerv/health_t.hpp"

namespace nerv {

class JsonWriter;

class ResourceTrend {
 public:
  // One health report, in log order. Reports without the gauges (older builds) are skipped.
  void add(const health_t& h);

  struct Process {
    int pid = 0;
    int restarts = 0;  // pids of this name seen before this one
    std::vector<std::pair<int64_t, double>> rss_series;  // (utime, rss_mb) of each report of this pid
    double cpu_sum = 0;  // of cpu_percent over the reports after the first
    double cpu_max = 0;
    int cpu_reports = 0;

    int reports() const { return static_cast<int>(rss_series.size()); }
    double spanS() const { return (rss_series.back().first - rss_series.front().first) / 1e6; }
    double rssFirstMb() const { return rss_series.front().second; }  // after the warm-up: sent at the first poll
    double rssLastMb() const { return rss_series.back().second; }
    double rssMaxMb() const;
    // The first report at least 60 s after the first one; nullptr before.
    const std::pair<int64_t, double>* settled() const;
    double rssSettledMb() const { return settled() ? settled()->second : 0; }
    double cpuMean() const { return cpu_reports > 0 ? cpu_sum / cpu_reports : 0; }
    // Whether the reports reach a minute past the settled one: enough for a growth figure.
    bool hasGrowth() const;
    // Memory growth per hour over the second half of the time after the first minute: a process
    // that leaks grows in both halves; its first minute fills caches and pools, and the allocator
    // may take one more step later (the soak in the README: the matcher +0.9 MiB once, at minute
    // 4 of 15), which is not growth. 0 until two minutes of reports.
    double growthMbPerHour() const;
  };
  const std::map<std::string, Process>& processes() const { return processes_; }

  // "resources": {"stixel/0": {"pid":..., "rss_first_mb":..., ...}, ...}
  void writeJson(JsonWriter& j) const;
  // One line per process.
  std::string text() const;

 private:
  std::map<std::string, Process> processes_;  // by "service/instance"
};

}  // namespace nerv

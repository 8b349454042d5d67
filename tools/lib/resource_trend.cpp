#include "resource_trend.hpp"

#include <algorithm>
#include <cstdio>

#include "json_writer.hpp"

namespace nerv {

namespace {

bool gaugeOf(const health_t& h, const char* name, double* value) {
  for (int i = 0; i < h.num_gauges && i < static_cast<int>(h.gauge_values.size()); ++i)
    if (h.gauge_names[i] == name) {
      *value = h.gauge_values[i];
      return true;
    }
  return false;
}

constexpr int64_t kSettleUs = 60'000'000;

}  // namespace

void ResourceTrend::add(const health_t& h) {
  double rss = 0, cpu = 0;
  if (!gaugeOf(h, "rss_mb", &rss)) return;
  const bool has_cpu = gaugeOf(h, "cpu_percent", &cpu);
  Process& p = processes_[h.service + "/" + h.instance];
  if (p.reports == 0 || p.pid != h.pid) {
    const int restarts = p.reports == 0 ? p.restarts : p.restarts + 1;
    p = Process{};
    p.restarts = restarts;
    p.pid = h.pid;
    p.first_utime = h.utime;
    p.rss_first_mb = rss;
  } else if (has_cpu) {  // the first report's share covers the warm-up since the start
    p.cpu_sum += cpu;
    p.cpu_max = std::max(p.cpu_max, cpu);
    ++p.cpu_reports;
  }
  if (p.settled_utime == 0 && h.utime - p.first_utime >= kSettleUs) {
    p.rss_settled_mb = rss;
    p.settled_utime = h.utime;
  }
  ++p.reports;
  p.rss_series.emplace_back(h.utime, rss);
  p.last_utime = h.utime;
  p.rss_last_mb = rss;
  p.rss_max_mb = std::max(p.rss_max_mb, rss);
}

double ResourceTrend::Process::growthMbPerHour() const {
  if (settled_utime == 0 || last_utime - settled_utime < kSettleUs) return 0;
  const int64_t middle = settled_utime + (last_utime - settled_utime) / 2;
  for (const auto& [utime, rss] : rss_series)
    if (utime >= middle) return utime < last_utime ? (rss_last_mb - rss) / ((last_utime - utime) / 3.6e9) : 0;
  return 0;
}

void ResourceTrend::writeJson(JsonWriter& j) const {
  j.key("resources");
  j.beginObject();
  for (const auto& [name, p] : processes_) {
    j.key(name);
    j.beginObject();
    j.field("pid", p.pid);
    j.field("restarts", p.restarts);
    j.field("reports", p.reports);
    j.field("span_s", (p.last_utime - p.first_utime) / 1e6);
    j.field("rss_first_mb", p.rss_first_mb);
    j.field("rss_settled_mb", p.rss_settled_mb);
    j.field("rss_last_mb", p.rss_last_mb);
    j.field("rss_max_mb", p.rss_max_mb);
    j.field("rss_growth_mb_per_hour", p.growthMbPerHour());
    j.field("cpu_percent_mean", p.cpuMean());
    j.field("cpu_percent_max", p.cpu_max);
    j.endObject();
  }
  j.endObject();
}

std::string ResourceTrend::text() const {
  std::string t;
  char buf[400];
  for (const auto& [name, p] : processes_) {
    std::snprintf(buf, sizeof buf,
                  "resources %-20s memory %.1f MiB at the first report, %.1f at the last, peak %.1f over %.0f s",
                  name.c_str(), p.rss_first_mb, p.rss_last_mb, p.rss_max_mb, (p.last_utime - p.first_utime) / 1e6);
    t += buf;
    if (p.settled_utime != 0 && p.last_utime - p.settled_utime >= kSettleUs) {
      std::snprintf(buf, sizeof buf, ", %.1f after the first minute, %+.1f MiB/h over the second half",
                    p.rss_settled_mb, p.growthMbPerHour());
      t += buf;
    }
    std::snprintf(buf, sizeof buf, "; CPU %.0f %% of a core on average, %.0f %% at most", p.cpuMean(), p.cpu_max);
    t += buf;
    if (p.restarts > 0)
      t += "; figures of pid " + std::to_string(p.pid) + ", after " + std::to_string(p.restarts) +
           (p.restarts == 1 ? " earlier process" : " earlier processes") + " of this name (a restart, a probe)";
    t += "\n";
  }
  return t;
}

}  // namespace nerv

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
  Process& p = processes_[h.service + "/" + h.instance];
  if (p.rss_series.empty() || p.pid != h.pid) {
    const int restarts = p.rss_series.empty() ? p.restarts : p.restarts + 1;
    p = Process{};
    p.restarts = restarts;
    p.pid = h.pid;
  } else if (gaugeOf(h, "cpu_percent", &cpu)) {  // the first report's share covers the warm-up since the start
    p.cpu_sum += cpu;
    p.cpu_max = std::max(p.cpu_max, cpu);
    ++p.cpu_reports;
  }
  p.rss_series.emplace_back(h.utime, rss);
}

double ResourceTrend::Process::rssMaxMb() const {
  double m = 0;
  for (const auto& [utime, rss] : rss_series) m = std::max(m, rss);
  return m;
}

const std::pair<int64_t, double>* ResourceTrend::Process::settled() const {
  for (const auto& report : rss_series)
    if (report.first - rss_series.front().first >= kSettleUs) return &report;
  return nullptr;
}

bool ResourceTrend::Process::hasGrowth() const {
  const auto* s = settled();
  return s && rss_series.back().first - s->first >= kSettleUs;
}

double ResourceTrend::Process::growthMbPerHour() const {
  if (!hasGrowth()) return 0;
  const int64_t last = rss_series.back().first;
  const int64_t middle = settled()->first + (last - settled()->first) / 2;
  for (const auto& [utime, rss] : rss_series)
    if (utime >= middle) return utime < last ? (rssLastMb() - rss) / ((last - utime) / 3.6e9) : 0;
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
    j.field("reports", p.reports());
    j.field("span_s", p.spanS());
    j.field("rss_first_mb", p.rssFirstMb());
    j.field("rss_settled_mb", p.rssSettledMb());
    j.field("rss_last_mb", p.rssLastMb());
    j.field("rss_max_mb", p.rssMaxMb());
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
                  name.c_str(), p.rssFirstMb(), p.rssLastMb(), p.rssMaxMb(), p.spanS());
    t += buf;
    if (p.hasGrowth()) {
      std::snprintf(buf, sizeof buf, ", %.1f after the first minute, %+.1f MiB/h over the second half",
                    p.rssSettledMb(), p.growthMbPerHour());
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

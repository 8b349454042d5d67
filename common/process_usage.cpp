#include "process_usage.hpp"

#include <sys/resource.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace nerv {

namespace {

double seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + t.tv_usec * 1e-6; }

// The process's start time, as microseconds since the epoch, for the first CpuShare interval.
int64_t processStartUtime() {
  std::ifstream stat("/proc/self/stat");
  std::string line;
  if (!std::getline(stat, line)) return 0;
  // Field 22 (starttime, clock ticks since boot) follows the command name in parentheses, which
  // may itself hold spaces and parentheses: count fields after the last ')'.
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return 0;
  unsigned long long start_ticks = 0;
  int field = 2;
  size_t pos = close + 1;
  while (pos < line.size() && field < 22) {
    while (pos < line.size() && line[pos] == ' ') ++pos;
    ++field;
    if (field == 22) {
      start_ticks = std::strtoull(line.c_str() + pos, nullptr, 10);
      break;
    }
    while (pos < line.size() && line[pos] != ' ') ++pos;
  }
  std::ifstream uptime_file("/proc/uptime");
  double uptime_s = 0;
  if (!(uptime_file >> uptime_s)) return 0;
  const long ticks_per_s = sysconf(_SC_CLK_TCK);
  if (ticks_per_s <= 0) return 0;
  timeval now{};
  gettimeofday(&now, nullptr);
  const double age_s = uptime_s - static_cast<double>(start_ticks) / ticks_per_s;
  return static_cast<int64_t>((seconds(now) - age_s) * 1e6);
}

}  // namespace

ProcessUsage readProcessUsage() {
  ProcessUsage u;
  rusage r{};
  if (getrusage(RUSAGE_SELF, &r) == 0) u.cpu_s = seconds(r.ru_utime) + seconds(r.ru_stime);
  // /proc/self/status computes the peak (VmHWM) as at least the resident set (VmRSS) of the same
  // read; getrusage's ru_maxrss and /proc/self/statm are updated at different moments and a
  // peak read from one can lie below a resident set read from the other.
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    double* target = line.rfind("VmRSS:", 0) == 0 ? &u.rss_mb : line.rfind("VmHWM:", 0) == 0 ? &u.rss_peak_mb : nullptr;
    if (target) *target = std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // kB
  }
  return u;
}

double CpuShare::percentSince(double cpu_s, int64_t now_utime) {
  if (last_utime_ == 0) last_utime_ = processStartUtime();
  const double wall_s = (now_utime - last_utime_) * 1e-6;
  const double used_s = cpu_s - last_cpu_s_;
  last_cpu_s_ = cpu_s;
  last_utime_ = now_utime;
  if (wall_s <= 1e-3 || used_s < 0) return 0;
  return 100.0 * used_s / wall_s;
}

}  // namespace nerv

// What this process costs the computer it runs on: resident memory and CPU time, read from
// the kernel (/proc/self/status, getrusage). Every service reports them in NERV_HEALTH as
// gauges, so a drive's log shows whether a stage grows over hours or takes more than its
// share of the cores (README "Memory and CPU of each process").
#pragma once

#include <cstdint>

namespace nerv {

struct ProcessUsage {
  double rss_mb = 0;       // resident set now [MiB]; 0 where /proc cannot be read
  double rss_peak_mb = 0;  // the largest resident set since the process started [MiB]
  double cpu_s = 0;        // user + system CPU time of all threads since start [s]
};

ProcessUsage readProcessUsage();

// CPU share between two calls: 100 = one core busy for the whole interval, up to 100 times the
// number of cores for a process whose threads all compute.
class CpuShare {
 public:
  // The share since the previous call (the first call: since the process started).
  double percentSince(double cpu_s, int64_t now_utime);

 private:
  double last_cpu_s_ = 0;
  int64_t last_utime_ = 0;
};

}  // namespace nerv

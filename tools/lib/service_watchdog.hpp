// A supervised service that stops sending NERV_HEALTH is hung: nerv_up kills and
// restarts it. Every service reports once a second from its message loop
// (lcm_node.hpp), so a process that is stopped, deadlocked or stuck in one
// frame goes silent while it still exists, and restarting only on exit never
// caught it: its status line said "silent" for as long as it lasted.
//
// Times are seconds on one monotonic clock. A process gets `startup_s` for its
// first report (warm-up, thread pools) and `silent_s` between reports after it.
// A service reports between frames, so one frame longer than `silent_s` is taken
// for a hang: the default matcher needs 1.8 s for the largest frame the limits
// let in (4096x3072, idle machine), OpenCV's 8-path SGBM 31 s (2026-12-06).
#pragma once

namespace nerv {

struct WatchdogSettings {
  double silent_s = 10.0;   // 0 = off; else at least 2 (reports come once a second)
  double startup_s = 30.0;  // allowance before the first report
};

class ServiceWatchdog {
 public:
  explicit ServiceWatchdog(const WatchdogSettings& settings = {}) : settings_(settings) {}

  // A new process of the service started at t.
  void started(double t);
  // A report of that process arrived at t (reports from before started() are ignored).
  void reported(double t);

  // Silent for longer than its allowance at `now` (never when the watchdog is off).
  bool hung(double now) const;
  // Seconds since the last report, or since the start before the first one.
  double silentFor(double now) const { return now - last_; }
  bool hasReported() const { return reported_; }

 private:
  WatchdogSettings settings_;
  double started_ = 0, last_ = 0;
  bool reported_ = false;
};

}  // namespace nerv

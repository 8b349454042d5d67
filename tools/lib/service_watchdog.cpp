#include "service_watchdog.hpp"

namespace nerv {

void ServiceWatchdog::started(double t) {
  started_ = last_ = t;
  reported_ = false;
}

void ServiceWatchdog::reported(double t) {
  if (t < started_) return;  // the previous process, or another one that had this pid
  reported_ = true;
  if (t > last_) last_ = t;
}

bool ServiceWatchdog::hung(double now) const {
  if (settings_.silent_s <= 0) return false;
  return silentFor(now) > (reported_ ? settings_.silent_s : settings_.startup_s);
}

}  // namespace nerv

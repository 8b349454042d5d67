#include "health_compat.hpp"

#include <cstdint>
#include <exception>

#include "message_fingerprint.hpp"
#include "nerv/health_v1_t.hpp"
#include "nerv/health_v2_t.hpp"

namespace nerv {

namespace {

template <class T>
bool decodeAs(const void* data, int size, T& msg) {
  try {  // a corrupt array length makes the generated decoder throw
    return msg.decode(data, 0, size) >= 0;
  } catch (const std::exception&) {
    return false;
  }
}

// The fields every layout has.
template <class Old>
void copyCommon(const Old& m, health_t& out) {
  out = health_t{};
  out.utime = m.utime;
  out.service = m.service;
  out.instance = m.instance;
  out.host = m.host;
  out.pid = m.pid;
  out.frames_in = m.frames_in;
  out.frames_out = m.frames_out;
  out.frames_dropped = m.frames_dropped;
  out.errors = m.errors;
  out.num_counters = m.num_counters;
  out.counter_names = m.counter_names;
  out.counter_values = m.counter_values;
  out.num_gauges = 0;
  out.latency_p50_ms = m.latency_p50_ms;
  out.latency_p95_ms = m.latency_p95_ms;
  out.processing_ms = m.processing_ms;
  out.status = m.status;
  out.last_error = m.last_error;
}

}  // namespace

bool decodeHealth(const void* data, int size, health_t& out, HealthLayout* layout) {
  const int64_t fp = messageFingerprint(data, size);
  HealthLayout which = HealthLayout::Unknown;
  bool ok = false;
  if (fp == health_t::getHash()) {
    ok = decodeAs(data, size, out);
    which = HealthLayout::Current;
  } else if (fp == health_v2_t::getHash()) {
    health_v2_t m;
    if ((ok = decodeAs(data, size, m))) {
      copyCommon(m, out);
      out.version = m.version;
    }
    which = HealthLayout::WithoutGauges;
  } else if (fp == health_v1_t::getHash()) {
    health_v1_t m;
    if ((ok = decodeAs(data, size, m))) {
      copyCommon(m, out);
      out.version = kVersionUnknown;
    }
    which = HealthLayout::WithoutVersion;
  }
  if (layout) *layout = ok ? which : HealthLayout::Unknown;
  return ok;
}

}  // namespace nerv

// NERV_HEALTH in any layout nerv has published. health_t gained `version` and then the gauges,
// and each change gave it a new fingerprint: a process of an older build on the bus (one
// computer of a vehicle not yet updated) and the NERV_HEALTH of logs recorded before were
// unknown messages to the current build. Its older layouts stay in lcmtypes/ (health_v1_t,
// health_v2_t; reading only), and this decodes a payload of any of them into the current
// layout, the fields it lacks left empty.
#pragma once

#include <string>

#include "nerv/health_t.hpp"

namespace nerv {

// Which layout a NERV_HEALTH payload had.
enum class HealthLayout {
  Current,
  WithoutGauges,   // health_v2_t: builds from d149867 until 9bb7c6e (2026-12-06)
  WithoutVersion,  // health_v1_t: builds before d149867 (no build stamp, no gauges)
  Unknown,         // none of them, or broken
};

// Decodes data[0, size) as whichever layout its fingerprint names; false (out unspecified) when
// it is none of them or its payload is broken. A report without a version gets
// kVersionUnknown as its version, so that a status line says so.
bool decodeHealth(const void* data, int size, health_t& out, HealthLayout* layout = nullptr);

constexpr const char* kVersionUnknown = "unknown (a build before version stamps)";

}  // namespace nerv

// Reading what the stereo_matcher's rig check says (services/stereo_matcher/rig_check.hpp) in tests.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "rig_check.hpp"

namespace nerv::stereo {

// The findings' names in order, "log" for a log line; gauges left out.
inline std::string findingNames(const std::vector<RigFinding>& findings) {
  std::string out;
  for (const RigFinding& f : findings)
    if (f.kind != RigFinding::Kind::Gauge) out += (out.empty() ? "" : " ") + (f.name.empty() ? "log" : f.name);
  return out;
}

// A gauge's value, NaN when the findings set none of that name.
inline double findingGauge(const std::vector<RigFinding>& findings, const std::string& name) {
  for (const RigFinding& f : findings)
    if (f.kind == RigFinding::Kind::Gauge && f.name == name) return f.value;
  return NAN;
}

// The first finding of this kind, nullptr when there is none.
inline const RigFinding* firstFinding(const std::vector<RigFinding>& findings, RigFinding::Kind kind) {
  for (const RigFinding& f : findings)
    if (f.kind == kind) return &f;
  return nullptr;
}

}  // namespace nerv::stereo

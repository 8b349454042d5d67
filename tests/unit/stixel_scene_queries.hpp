// Shared query of the stixel tests on painted scenes: the hypothesis at a depth
// over given columns.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "perception_types.hpp"

namespace nerv::stixel {

// The hypothesis at depth z (within tol_m) whose box overlaps columns [u0, u1), if any.
inline std::optional<Hypothesis> hypothesisAt(const std::vector<Hypothesis>& hs, float z, int u0, int u1,
                                              float tol_m = 1.5f) {
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < tol_m && h.box.x < u1 && h.box.x + h.box.w > u0) return h;
  return std::nullopt;
}

}  // namespace nerv::stixel

// Classifies each stixel hypothesis from its surface-normal statistics as
// object, ground or disparity error (NERV reference slides 12-14, 32-33).
#pragma once

#include <vector>

#include "config.hpp"
#include "perception_types.hpp"

namespace nerv::validator {

struct Params {
  float min_object_fraction = 0.3f;   // keep when at least this share of normals is upright
  float max_ground_fraction = 0.6f;   // reject as ground above this share of ground-like normals
  float max_error_fraction = 0.6f;    // reject as error above this share of error-like normals
  int min_normals = 5;                // fewer normals: not enough evidence
};

Params readParams(ConfigSection& section);

// stats may be null (no normals for this ROI): the verdict is "unvalidated".
Verdict classify(const Hypothesis& hypothesis, const NormalStats* stats, const Params& params);

// One verdict per hypothesis, in order; stats are matched by roi_id.
std::vector<Verdict> validate(const std::vector<Hypothesis>& hypotheses,
                              const std::vector<NormalStats>& stats, const Params& params);

}  // namespace nerv::validator

// Classifies each stixel hypothesis from its surface-normal statistics as
// object, ground or disparity error (NERV reference slides 12-14, 32-33).
#pragma once

#include <vector>

#include "config.hpp"
#include "duplicates.hpp"
#include "pole_parts.hpp"
#include "perception_types.hpp"

namespace nerv::validator {

struct Params {
  float min_object_fraction = 0.3f;   // keep when at least this share of normals is upright
  float max_ground_fraction = 0.6f;   // reject as ground above this share of ground-like normals ...
  int min_ground_normals = 10;        // ... out of at least this many normals
  float max_error_fraction = 0.6f;    // reject as error above this share of error-like normals
  int min_normals = 5;                // fewer normals: not enough evidence
  float min_error_density = 0.5f;     // "error" needs at least this normals/samples density (dense blobs)
  bool keep_unvalidated = true;       // keep hypotheses without enough normals (a planner never loses one silently)
  float min_unvalidated_height_m = 0.8f;  // ... except when normals were measured but too few or mixed and the box
                                          // is lower than this (kerb, bush, lawn clutter); 0 = keep all
  float min_height_m = 0.2f;          // metric height below this (when known, > 0) is implausible -> error
  float max_height_m = 4.5f;          // metric height above this is implausible -> error ...
  float pole_max_width_m = 1.2f;      // ... unless narrower than this: a pole or post (sign and tram-wire
                                      // poles stand 5-10 m); 0 = no exception
  float max_width_m = 12.0f;          // metric width above this is implausible -> error
  // A surface only tilted from the road (lawn, verge, kerb, ramp): representative
  // normal within max_surface_tilt_deg of the ground normal while object normals
  // stay below min_object_fraction, on at least min_surface_normals normals.
  // Chosen on kitti_raw_0926_seq (docs/validator.md); 0 disables the rule.
  float max_surface_tilt_deg = 15.0f;
  int min_surface_normals = 20;
  // ... only this near: normal angles degrade with depth noise (~z^2), and a car
  // front at 40 m measures 10-15 deg from the road. 0 = no limit.
  float max_surface_tilt_distance_m = 30.0f;
  // Second boxes on one object (same rows and depth, IoU above min_iou): the
  // one with fewer normals is removed (duplicates.hpp). min_iou 0 = off.
  DuplicateParams duplicates;
  // Parts of one pole boxed twice (narrow, tall, same columns and depth): the
  // shorter is removed (pole_parts.hpp); narrow means below pole_max_width_m.
  PolePartParams pole_parts;
};

Params readParams(ConfigSection& section);

// stats may be null (no normals for this ROI): the verdict is "unvalidated".
Verdict classify(const Hypothesis& hypothesis, const NormalStats* stats, const Params& params);

// One verdict per hypothesis, in order; stats are matched by roi_id. Then
// second boxes on one object are removed (duplicates.hpp).
std::vector<Verdict> validate(const std::vector<Hypothesis>& hypotheses,
                              const std::vector<NormalStats>& stats, const Params& params);

}  // namespace nerv::validator

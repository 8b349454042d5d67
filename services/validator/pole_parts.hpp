// Parts of one pole boxed twice. A sign or tram-wire pole can come out of the
// stixel stage as two or three narrow hypotheses at its depth: the post's own
// tower, the group it stood in and a second-layer piece above an occluder,
// each with its own top and foot (KITTI 0926 frame 4: boxes 3.1, 4.4 and 4.9 m
// tall over the same columns at 12.0-13.4 m). They differ in rows by more
// than the duplicate check allows (duplicates.hpp), so each was kept. Two kept
// boxes that are both pole-like (narrower than pole_max_width_m, at least
// min_height_m tall), share at least min_overlap of the narrower one's columns
// and lie within max_depth_ratio in depth are one pole: the shorter is removed
// (a pole's box is its whole height), on equal height the one with fewer normals.
// Road users are not pole-like (under 2 m), so they are never compared. 2.4 m, not
// 2.5: KITTI 0926 frame 5's post against saturated sky also comes as a 2.46 m box.
#pragma once

#include <vector>

#include "perception_types.hpp"

namespace nerv::validator {

struct PolePartParams {
  float min_height_m = 2.4f;      // both boxes at least this tall [m] (a road user is not); 0 = off
  float max_depth_ratio = 0.15f;  // depths this close, relative to the nearer
  float min_overlap = 0.5f;       // shared columns over the narrower box's width
};

// verdicts[i] belongs to hypotheses[i]; normals[i] is its number of normals;
// pole_max_width_m is the validator's (what a pole is for its height check).
// Removed ones get the reason "part of the pole of hypothesis N (...)".
// Returns how many were removed.
int removePoleParts(const std::vector<Hypothesis>& hypotheses, const std::vector<int>& normals,
                    std::vector<Verdict>& verdicts, const PolePartParams& params, float pole_max_width_m);

}  // namespace nerv::validator

// Adaptive mean shift on a 1D sample (NERV slides 25-26): start at the
// histogram mode; the radius is chosen so the window holds `fraction` of all
// samples around the current centre; the centre moves to those inliers' mean;
// repeat until it moves less than `stop_deg`.
#pragma once

#include <vector>

namespace nerv::snv {

struct MeanShiftResult {
  float start = 0;      // where it began (the mode)
  float estimate = 0;   // converged centre (inlier mean)
  float radius = 0;     // final window half-width
  int inliers = 0;      // samples in the final window
  int iterations = 0;
  bool converged = false;
};

// The `count` = max(1, ceil(fraction * n)) samples nearest to `centre` form a
// contiguous run of the sorted sample; returns its first index.
int nearestRunBegin(const std::vector<float>& sorted, float centre, int count);

// sorted: ascending, non-empty. fraction in (0, 1].
MeanShiftResult adaptiveMeanShift(const std::vector<float>& sorted, float start, float fraction,
                                  float stop, int max_iterations = 100);

}  // namespace nerv::snv

// Super-SNV (NERV slides 22-24): every ground-class normal becomes a pitch and
// a roll angle; their histograms at 0.1 deg bins give the mode that starts the
// adaptive mean shift.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace nerv::snv {

// Camera pitch implied by a road normal n (unit, pointing up: n_y < 0), positive
// when the camera looks down. The reference writes pitch = 90 deg - acos(z / sqrt(y^2 + z^2));
// with y down and the normal pointing up that angle has the opposite sign, so
// pitch = acos(n_z / sqrt(n_y^2 + n_z^2)) - 90 deg = atan2(-n_z, -n_y).
inline float normalPitchDeg(const cv::Vec3f& n) {
  return static_cast<float>(std::atan2(-n[2], -n[1]) * 180.0 / CV_PI);
}
// Camera roll, positive = clockwise as seen from behind (the camera's x axis
// dips towards the road): roll = atan2(-n_x, -n_y).
inline float normalRollDeg(const cv::Vec3f& n) {
  return static_cast<float>(std::atan2(-n[0], -n[1]) * 180.0 / CV_PI);
}
// The unit road normal (pointing up) for a camera pitch and roll; inverse of the two above.
cv::Vec3f normalFromPitchRoll(float pitch_deg, float roll_deg);

// Histogram of angles at bin_deg bins; bin k covers [origin + k*bin, origin + (k+1)*bin).
struct AngleHistogram {
  float bin_deg = 0.1f;
  float origin_deg = 0;
  std::vector<int> counts;
  // Centre of the fullest bin (the first one on ties); NaN when empty.
  float modeDeg() const;
};

// Bins are aligned to multiples of bin_deg. values may be in any order.
AngleHistogram buildAngleHistogram(const std::vector<float>& values_deg, float bin_deg);

// --- fast paths of the super-SNV (references: the functions above, std::sort) ---

// normalPitchDeg / normalRollDeg of `count` normals at once: a vectorisable
// atan (Cephes atanf polynomial, < 2e-7 rad) wherever -n_y > 0 (every ground
// normal), std::atan2 elsewhere.
void normalAnglesDeg(const cv::Vec3f* normals, int count, float* pitch_deg, float* roll_deg);

// Smallest and largest of v[0, n) (NaN when n = 0; NaNs in v are skipped).
void sampleRange(const float* v, size_t n, float& lo, float& hi);

// Ascending sort of finite floats in ~O(n) for angle samples: a recursive
// bucket sort, n buckets evenly spaced over [min, max] per level (std::sort
// below depth 6 or on non-finite values).
void sortAngles(std::vector<float>& values_deg);

// buildAngleHistogram(sorted, bin_deg).modeDeg() read from an ascending sample in
// one pass without building the histogram (same bins, same tie rule).
float sortedModeDeg(const std::vector<float>& sorted_deg, float bin_deg);

}  // namespace nerv::snv

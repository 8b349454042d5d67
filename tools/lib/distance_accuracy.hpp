// How far off the reported distance of a detection is, for whoever feeds the
// detections to a planner: for every true positive, its depth (z_m, the
// optical-axis distance of the hypothesis' base point at its median stixel, or
// nearest_z_m, its nearest part; both on the surface the camera sees) against the labelled object's
// nearest depth, the smallest z over the four bottom corners of its 3D box
// (KITTI: location = bottom centre, length along the heading, rotation_y about
// the camera's y axis). A car seen from behind is then compared at its rear
// bumper, not at its centre half a car length farther. Labels without a 3D size
// (the KITTI raw set here gives only z) are compared at their z as given. Only
// fully visible objects are compared (labelDepthComparable): a truncated or
// occluded object's nearest corner may lie outside the image or behind the
// occluder, nearer than anything the camera sees of it. Errors are summarised
// per range band of the truth.
#pragma once

#include <string>
#include <vector>

#include "kitti_labels.hpp"

namespace nerv {

// Nearest depth [m] of a labelled object; <= 0 when the label has no depth.
float labelNearestDepth(const KittiLabel& label);

// Neither truncated nor occluded, and with a depth.
bool labelDepthComparable(const KittiLabel& label);

struct DistanceErrorBand {
  float from_m = 0, to_m = 0;  // truth in [from_m, to_m)
  int count = 0;
  double bias_m = 0;           // mean of estimate - truth
  double median_abs_m = 0;     // median |estimate - truth|
  double p95_abs_m = 0;        // 95th percentile of |estimate - truth|
  double median_rel = 0;       // median |estimate - truth| / truth
  // Against the estimate's own 1-sigma (nearest_z_sigma_m), over the samples that
  // have one (count_with_sigma): the shares within 1 and 2 sigma (a calibrated
  // sigma gives about 0.68 and 0.95) and the 68th percentile of |error| / sigma
  // (about 1 when calibrated; above 1: the sigma is too small).
  int count_with_sigma = 0;
  double within_1sigma = 0, within_2sigma = 0;
  double p68_abs_over_sigma = 0;
};

class DistanceAccuracy {
 public:
  // Ignored unless both are finite and positive. sigma_m: the estimate's 1-sigma
  // uncertainty, 0 when it has none.
  void add(float truth_m, float estimate_m, float sigma_m = 0);
  int count() const { return static_cast<int>(truth_.size()); }
  // One band per pair of neighbouring edges (ascending), then one from the
  // last edge on; bands without samples are left out.
  std::vector<DistanceErrorBand> bands(const std::vector<float>& edges_m) const;

 private:
  std::vector<float> truth_, estimate_, sigma_;
};

// The default bands: 0-10, 10-20, 20-30, 30-40 m and beyond.
const std::vector<float>& defaultDistanceBands();

// Both depths of the kept true positives: z_m (median stixel) and nearest_z_m
// (nearest part, with its nearest_z_sigma_m), against the label's nearest depth;
// labels that are not labelDepthComparable are left out.
struct DepthErrors {
  DistanceAccuracy z, nearest;
  void add(const KittiLabel& label, float z_m, float nearest_z_m, float nearest_z_sigma_m = 0);
  int count() const { return z.count(); }
  // Both tables over the default bands, each under a heading line.
  std::string format() const;
};

// "  0-10 m  n 12  bias +0.05 m  median |err| 0.08 m  p95 0.21 m  median 1.1 %" per band,
// then "  within 1 / 2 sigma 67 / 94 %  |err|/sigma p68 1.02" when the band has sigmas.
std::string formatDistanceBands(const std::vector<DistanceErrorBand>& bands);

}  // namespace nerv

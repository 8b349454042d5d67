// Normal statistics of one hypothesis ROI (NERV slides 12-14; fields as in
// lcmtypes/normal_stats_t.lcm). Every normal falls in at most one class:
//
//  ground-like  angle to the ground normal g <= ground_tolerance_deg.
//  facing       otherwise, within facing_cone_deg of the camera's -z axis: the
//               surface is parallel to the image plane (constant disparity), the
//               normal has no horizontal (x) and no vertical (y) component.
//               Constant-disparity blobs that SGBM's smoothness term paints over
//               textureless areas look exactly like this.
//  upright      otherwise, angle to g within 90 +- upright_tolerance_deg: a
//               vertical surface turned away from the line of sight (car sides
//               and corners, round poles) - an object with a horizontal component.
//
// A ROI is upright-consistent when its upright normals make up at least
// upright_consistency_fraction of its normals: a real object shows some surface
// turned away from the camera. In such a ROI the facing normals are object
// surfaces (a car's rear) and count as object-like when they are also upright;
// in a ROI that is not upright-consistent they count as error-like.
//   object_fraction = (upright + [consistent] facing-and-upright) / num_normals
//   error_fraction  = [not consistent] facing / num_normals
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "local_normals.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv {

struct RoiStatsParams {
  float ground_tolerance_deg = 15.0f;         // within this of the ground normal = ground-like
  float upright_tolerance_deg = 30.0f;        // within 90 +- this of the ground normal = upright
  float facing_cone_deg = 10.0f;              // within this of the camera's -z axis = facing
  float upright_consistency_fraction = 0.15f; // share of upright normals that makes a ROI an object
};

// num_samples: grid pixels of the ROI inside the image. A ROI without samples
// or normals gets zero counts, fractions and normal (explicitly "no evidence").
NormalStats computeRoiStats(int roi_id, int num_samples, const std::vector<LocalNormal>& normals,
                            const cv::Vec3f& ground_normal,
                            const RoiStatsParams& params);

}  // namespace nerv::snv

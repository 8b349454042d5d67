// Camera height over the road: the robust (median) distance of the ground
// points to the plane through the camera with the estimated road normal.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace nerv::snv {

// points: ground points in the camera frame [m]; normal: unit road normal
// pointing up. Height of each point = -n . P (the road lies below the camera,
// against the normal). Returns NaN when points is empty.
float medianCameraHeight(const std::vector<cv::Vec3f>& points, const cv::Vec3f& normal);

}  // namespace nerv::snv

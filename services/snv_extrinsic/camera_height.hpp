// Camera height over the road: the robust (median) distance of the ground
// points to the plane through the camera with the estimated road normal.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace nerv::snv {

// Median of a sample (mean of the two middle values when the size is even);
// NaN when empty. Equal to std::nth_element's; in ~O(n): a counting pass over
// n/16 buckets narrows the selection to the buckets holding the middle ranks.
// Works on a partial copy; `values` is not changed.
float sampleMedian(const std::vector<float>& values);

// points: ground points in the camera frame [m]; normal: unit road normal
// pointing up. Height of each point = -n . P (the road lies below the camera,
// against the normal). Returns NaN when points is empty.
float medianCameraHeight(const std::vector<cv::Vec3f>& points, const cv::Vec3f& normal);

}  // namespace nerv::snv

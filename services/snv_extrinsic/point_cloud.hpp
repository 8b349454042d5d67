// Organised point cloud P_x, P_y, P_z from a disparity map (NERV slide 11):
// every pixel keeps its place, so neighbours in the image are neighbours in 3D.
#pragma once

#include <opencv2/core.hpp>

#include "stereo_camera.hpp"

namespace nerv::snv {

struct PointCloud {
  cv::Mat x, y, z;  // CV_32F, same size as the disparity, metres; NaN where disparity is invalid
};

// True where a disparity value can be turned into a point (finite and > 0).
inline bool validDisparity(float d) { return d > 0.0f && d < 1e6f; }

// disparity: CV_32F, <= 0 or non-finite = invalid.
PointCloud computePointCloud(const cv::Mat& disparity, const StereoCamera& cam);

}  // namespace nerv::snv

// Exact disparity of a flat road with upright boxes, seen from a pitched camera.
// A fixture for the stixel tests and the benchmark: ground truth is known by
// construction (foot rows, depths, camera pose), independent of the estimator.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "stereo_camera.hpp"

namespace nerv::stixel {

// An upright box face facing the camera: level-frame depth z_m, lateral extent
// [x_left_m, x_right_m], standing on the road, height_m tall.
struct SceneBox {
  float z_m = 10, x_left_m = -1, x_right_m = 1, height_m = 1.5f;
};

struct RoadScene {
  float camera_height_m = 1.65f;
  float pitch_deg = 0;          // positive: camera looks down
  bool has_road = true;
  std::vector<SceneBox> boxes;
};

// Ray cast per pixel: CV_32F disparity, 0 where the ray meets nothing (sky).
cv::Mat renderDisparity(const RoadScene& scene, const StereoCamera& cam);

// Row (sub-pixel) where the road point at level-frame depth z_m projects.
double footRow(const RoadScene& scene, const StereoCamera& cam, double z_m);

// Columns [u0, u1) of a face painted into `disp`.
struct FaceColumns {
  int u0 = 0, u1 = 0;
};

// Paints an upright face at level-frame depth z_m over [x_left_m, x_right_m] x
// [bottom_m, top_m] over the road (a post, a plate, a crown floating over it)
// with its exact disparity, rows clipped to the image top.
FaceColumns paintFace(cv::Mat& disp, const RoadScene& scene, const StereoCamera& cam, float z_m, double x_left_m,
                      double x_right_m, double bottom_m, double top_m);

// KITTI raw 2011-09-26 colour camera pair.
StereoCamera kittiLikeCamera();

}  // namespace nerv::stixel

// A frame to warm a service up with at start. A service's first frame took 3-5
// times its usual time (the matcher 90-130 ms against 25-30, snv_extrinsic 17-73
// against 2-5, the stixel stage 18-27 against 1-5): its buffers are allocated
// and page-faulted, thread pools started, on the first call of each instance.
// At the camera's 10 Hz the next frames queued behind it, and the first ones
// after a start (or a supervisor's restart) reached DETECTIONS 180-295 ms after
// capture instead of 40-50 (README "Start-up"). With the top-level config key
// `warmup: {width, height}` (the camera's image size) each service runs its
// algorithm once on the frames below before it subscribes; a frame of another
// size is as slow as before.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv {

struct WarmupSize {
  int width = 0, height = 0;  // 0 = no warm-up
  bool on() const { return width > 0 && height > 0; }
};

// A camera of that size with KITTI's proportions (fx = fy = 0.58 width, the
// principal point in the middle, baseline 0.54 m).
StereoCamera warmupCamera(const WarmupSize& size);

// A textured 8-bit pair, the right view the left shifted by 16 px: every
// disparity level is searched as on a real frame.
void warmupPair(const WarmupSize& size, cv::Mat& left, cv::Mat& right);

// CV_32F disparity (0 = invalid) of what the camera sees 1.65 m over a flat
// road: the road below the horizon, a 2 m wide, 1.5 m tall box at 15 m ahead
// and a wall 40 m away above the horizon, so that ground fit, stixels and
// normals all run.
cv::Mat warmupDisparity(const StereoCamera& cam);

// The road of warmupDisparity as the stixel stage reports it, and the box as
// its one hypothesis (for snv_extrinsic, which takes both from STIXELS).
GroundModel warmupGround(const StereoCamera& cam);
std::vector<Hypothesis> warmupHypotheses(const StereoCamera& cam);

}  // namespace nerv

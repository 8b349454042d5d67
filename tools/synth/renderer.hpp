// Ray-casting renderer of a rectified stereo pair with exact ground truth.
//
// Both views use the same intrinsics; the right camera sits `baseline_m` along
// the left camera's x axis. Primary rays are d = x r + y dn + f (camera frame
// (x, y, 1)), so the ray parameter t of a hit is its depth Z and the left
// disparity is fx B / t exactly. Colours are supersampled (ss x ss samples per
// pixel); ground truth comes from the ray through the pixel centre.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "camera_pose.hpp"
#include "world.hpp"

namespace nerv::synth {

struct RenderOptions {
  // Anti-aliasing: 1 = pixel centre only, 2 = quincunx (centre + shared corners,
  // 2 rays per pixel), k >= 3 = k x k grid (slow reference).
  int supersample = 2;
  int threads = 0;      // 0 = OpenCV's thread pool, 1 = the calling thread only
  int label_min_run_px = 0;  // labels: box edges only on rows/columns seeing this many object pixels (0 = every pixel)
  // The right view taken this much later than the left [s] (negative: earlier): a rig whose
  // shutters are not triggered together. The labels, the true disparity and the pose are the
  // left view's.
  double right_delay_s = 0;
};

struct RenderedFrame {
  cv::Mat left, right;   // CV_8UC3 BGR with sensor noise and the right camera's gain
  cv::Mat disparity;     // CV_32F, left view, fx B / Z; 0 where the pixel sees sky
  cv::Mat object_id;     // CV_32S index into World::solids seen at the pixel centre, -1 = ground or sky
  cv::Mat trap_mask;     // CV_8U, 255 where the pixel centre lies in a disparity trap
  std::vector<int> unoccluded_px;  // per solid: pixel centres whose ray meets it, ignoring other solids
};

RenderedFrame renderFrame(const World& world, const CameraRig& rig, const CameraPose& pose,
                          int frame, uint64_t seed, const RenderOptions& options = {});

}  // namespace nerv::synth

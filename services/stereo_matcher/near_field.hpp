// Near field beyond the search range. The matcher searches disparities below
// reach = min_disparity + num_disparities (KITTI: 128 px, 3.0 m). A surface
// nearer than that has no match there, and it does not simply come out
// invalid: in front of a textured plane at 20 px a box at 200 px read 16-23 px
// (the plane's disparity, carried in by the paths) over 80 % of its pixels, at
// 160 px over 60 % - a near obstacle seen as far background. A car 2.4 m ahead
// in the `near_car` scene (160-167 px) came out all invalid and was missed in
// every frame (docs/stereo.md "Near field"). A second match at a quarter of
// the resolution covers [0, 4 x 64) = [0, 256) full-resolution pixels for a
// sixteenth of the pixels and half the levels (about 1 ms on two threads at
// 1242 x 375); wherever it sees a surface beyond the reach, its value replaces
// the full-resolution one, which cannot be right there. Nowhere else does it
// change anything: on the 11 KITTI and 270 synthetic frames of the evaluation
// (nothing nearer than 3 m) not one pixel differs.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

struct NearFieldParams {
  int scale = 4;               // resolution factor of the near-field match
  float reach_px = 128.0f;     // the full-resolution search reaches disparities below this
  float margin_px = 4.0f;      // near-field values from reach_px + margin_px up replace (one quarter-resolution step)
};

// full_disparity / full_confidence: CV_32F at full resolution (0 = invalid), updated in
// place. near_disparity / near_confidence: CV_32F at full / scale (rounded up), values in
// near-field pixels (multiplied by scale here). Returns the number of pixels replaced.
int fuseNearField(cv::Mat& full_disparity, cv::Mat& full_confidence, const cv::Mat& near_disparity,
                  const cv::Mat& near_confidence, const NearFieldParams& params);

}  // namespace nerv::stereo

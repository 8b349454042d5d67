// Foreground fattening correction. A window-based matching cost (census,
// SAD block) lets pixels up to half a window outside an object see the
// object's texture and take its disparity, so every object comes out
// wider by up to half a window on each side (census 9x7: 4 px, which is
// the whole width of a post at 20 m). At each foreground boundary of a row
// the true edge is the strongest intensity step within that band; the
// fattened pixels between it and the boundary are invalidated.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

struct BoundarySnapParams {
  int band_px = 4;         // how far inside a boundary the true edge may lie (half the window)
  float jump_px = 1.5f;    // disparity drop that makes a boundary (an invalid neighbour also does)
  int min_step = 8;        // weakest intensity step accepted as the object's edge (gray levels)
  int hole_search_px = 16; // across an invalid run, look this far for the next valid pixel
};

// gray: CV_8U, disparity: CV_32F (0 = invalid), confidence: CV_32F or empty.
// Returns the number of pixels invalidated.
int snapDisparityBoundaries(const cv::Mat& gray, cv::Mat& disparity, cv::Mat& confidence,
                            const BoundarySnapParams& params);

}  // namespace nerv::stereo

// Robust fit of the road line in a v-disparity image: Hough voting over the
// physically possible lines finds the dominant one, iteratively reweighted least
// squares (Huber weights) refines it on its inliers, and a pose check rejects
// lines that no camera on a vehicle could produce.
#pragma once

#include <string>

#include "stereo_camera.hpp"
#include "v_disparity.hpp"

namespace nerv::stixel {

struct GroundLineFitParams {
  float min_camera_height_m = 0.5f;    // lines implying a lower camera are rejected
  float max_camera_height_m = 4.0f;    // lines implying a higher camera are rejected
  float max_pitch_deg = 10.0f;         // lines implying a steeper |pitch| are rejected
  float inlier_tolerance_px = 1.5f;    // cells this close (disparity) to the line are inliers ...
  float obstacle_side_tolerance_px = 0.0f; // ... but cells above the line (nearer than the road: the feet
                                       // of obstacles, kerbs, the road beside a car) only within this
                                       // in the reweighted fit; 0 = inlier_tolerance_px on both sides
  int min_inlier_rows = 20;            // fewer image rows with inliers: weak fit
  float min_disparity_span_px = 5.0f;  // inliers must cover this disparity range (walls do not)
  float min_cell_fraction = 0.01f;     // cells with fewer pixels than this share of the width do not vote
  int max_cells_per_row = 4;           // only a row's strongest cells vote
};

struct GroundLine {
  bool ok = false;
  float slope = 0, intercept = 0;      // d = slope*v + intercept
  int inlier_cells = 0;
  int inlier_rows = 0;
  float residual_px = 0;               // weighted RMS of the inlier residuals
  std::string reason;                  // why the fit was rejected (empty when ok)
};

GroundLine fitGroundLine(const VDisparity& vd, const StereoCamera& cam,
                         const GroundLineFitParams& params);

}  // namespace nerv::stixel

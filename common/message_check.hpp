// Validation of received messages before any stage uses them. A failed check
// names the counter it is reported under in health and says what was wrong.
#pragma once

#include <string>

#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

namespace nerv {

struct Limits {
  int max_width = 4096;   // largest accepted image width [px]
  int max_height = 3072;  // largest accepted image height [px]
};

struct Problem {
  std::string counter;  // "" = no problem
  std::string message;
  explicit operator bool() const { return !counter.empty(); }
};

Problem checkCalibration(const stereo_calibration_t& calib, const Limits& limits);
Problem checkImage(const image_t& image, const Limits& limits, const char* which);
Problem checkStereoFrame(const stereo_frame_t& msg, const Limits& limits);
Problem checkDisparity(const disparity_t& msg, const Limits& limits);
Problem checkStixels(const stixels_t& msg, const Limits& limits);
Problem checkSurfaceNormals(const surface_normals_t& msg);
Problem checkExtrinsics(const extrinsics_t& msg);

}  // namespace nerv

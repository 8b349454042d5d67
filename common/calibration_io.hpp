// Reading stereo calibration from the file formats nerv meets in the field.
#pragma once

#include <stdexcept>
#include <string>

#include "stereo_camera.hpp"

namespace nerv {

struct CalibrationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Plain layout `calib.yaml`: width, height, fx, fy, cx, cy, baseline_m
// (camera_height_m optional, informative).
StereoCamera loadPlainCalibration(const std::string& path);

// KITTI raw `calib_cam_to_cam.txt`: P_rect_0L, P_rect_0R and S_rect_0L of the
// given camera indices (2/3 = colour, 0/1 = gray). Baseline from the P matrices'
// fourth column: B = (P_L[0][3] - P_R[0][3]) / fx.
StereoCamera loadKittiRawCalibration(const std::string& path, int left_index = 2,
                                     int right_index = 3);

// KITTI object/stereo `calib/NNNNNN.txt`: lines P2: and P3: (3x4 row-major).
// The file has no image size; it is given by the caller.
StereoCamera loadKittiObjectCalibration(const std::string& path, int width, int height);

}  // namespace nerv

// Reading raw (unrectified) stereo calibration for rectification on ingest.
#pragma once

#include <string>

#include "calibration_io.hpp"
#include "rectification.hpp"

namespace nerv {

// OpenCV FileStorage (YAML/XML) as written by the stereo_calib sample:
// M1 D1 M2 D2 R T (T in the unit of the calibration target, here metres).
// Image size from image_width/image_height, width/height or imageSize [w, h];
// when the file has none, `width`/`height` are used (> 0). Throws CalibrationError.
RawStereoCalibration loadOpenCvStereoCalibration(const std::string& path, int width = 0,
                                                 int height = 0);

// KITTI raw calib_cam_to_cam.txt: K_0i, D_0i, R_0i, T_0i, S_0i of the two
// cameras. KITTI gives each camera's pose relative to camera 0 (X_i = R_0i X_0 +
// T_0i), so the left->right pose is composed: R = R_r R_l^T, T = T_r - R T_l.
RawStereoCalibration loadKittiRawStereoCalibration(const std::string& path, int left_index = 2,
                                                   int right_index = 3);

}  // namespace nerv

// Stereo sequences on disk in the three layouts nerv reads:
//   plain         left/ right/ calib.yaml [label_2/ disp_gt/]
//                 or left/ right/ raw_calib.yaml: raw (distorted, unaligned) views with the
//                 rig's calibration (OpenCV stereo_calib file), rectified by the receiver
//   KITTI raw     image_02/data image_03/data, calib_cam_to_cam.txt here or one level up
//                 (rectified "sync" images; images of the raw size S_02, the unrectified
//                 "extract" downloads, are raw views with K/D/R/T of cameras 2 and 3)
//   KITTI object  image_2/ image_3/ calib/NNNNNN.txt [label_2/ disp_occ_0/]
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rectification.hpp"
#include "stereo_camera.hpp"

namespace nerv {

struct DatasetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DatasetFrame {
  std::string name;          // file stem, e.g. "0000000003"
  std::string left_path;
  std::string right_path;
  std::string label_path;    // KITTI label_2 text file, empty if none
  std::string disp_gt_path;  // ground-truth disparity PNG (uint16 x256 or 8-bit), empty if none
  StereoCamera camera;       // rectified calibration of this frame
  // Set when the images are raw (raw_calib.yaml, KITTI extract): they must be rectified before matching
  // (the stereo_matcher service does it on ingest), and `camera` is the rectified camera
  // that rectification gives.
  std::optional<RawStereoCalibration> raw;
};

struct Dataset {
  std::string root;
  std::string layout;        // "plain" | "kitti_raw" | "kitti_object"
  std::vector<DatasetFrame> frames;  // sorted by name
};

// Throws DatasetError (missing folder, unknown layout, no frames, missing
// right image or calibration, both calib.yaml and raw_calib.yaml) with a one-line message.
Dataset openDataset(const std::string& dir);

}  // namespace nerv

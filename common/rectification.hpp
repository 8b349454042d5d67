// Rectification on ingest: a raw (distorted, unaligned) stereo pair with full
// calibration becomes a rectified pair whose rows are epipolar lines
// (cv::stereoRectify, Bouguet's method), plus the rectified pinhole camera the
// disparity refers to. The undistort/rectify maps are computed once per
// calibration and cached.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstddef>
#include <list>
#include <string>

#include "stereo_camera.hpp"

namespace nerv {

// Raw calibration of a stereo rig. A point X in the left camera frame is
// R * X + T in the right camera frame (OpenCV stereoCalibrate convention).
struct RawStereoCalibration {
  int width = 0, height = 0;     // raw image size [px]
  std::array<double, 9> left_K{};   // row-major intrinsic matrix [px]
  std::array<double, 5> left_D{};   // k1 k2 p1 p2 k3
  std::array<double, 9> right_K{};
  std::array<double, 5> right_D{};
  std::array<double, 9> R{};        // row-major rotation left -> right
  std::array<double, 3> T{};        // translation left -> right [m]

  // Empty when usable, else one line naming the first problem.
  std::string problem() const;
  bool operator==(const RawStereoCalibration& o) const;
};

// The rectification of one calibration: maps for both views and the result.
struct Rectification {
  RawStereoCalibration raw;
  cv::Mat left_map1, left_map2, right_map1, right_map2;  // initUndistortRectifyMap, CV_16SC2
  cv::Mat R1, R2, P1, P2;                                // stereoRectify outputs
  StereoCamera camera;                                   // rectified camera (same image size)
};

// Computes the rectification (alpha = 0: only valid pixels, no black border).
// Throws std::invalid_argument when raw.problem() is not empty, OpenCV cannot
// rectify it or the rectified camera is unusable (StereoCamera::problem()).
Rectification computeRectification(const RawStereoCalibration& raw);

// Cache of the last few rectifications, keyed by the whole calibration.
class Rectifier {
 public:
  explicit Rectifier(std::size_t capacity = 4) : capacity_(capacity) {}
  // Maps for this calibration (computed on first use; throws as computeRectification).
  const Rectification& get(const RawStereoCalibration& raw);
  // Rectifies both images (any type remap accepts). Returns the rectified camera.
  const StereoCamera& rectify(const RawStereoCalibration& raw, const cv::Mat& left,
                              const cv::Mat& right, cv::Mat& left_out, cv::Mat& right_out);
  // The left view alone (what is drawn on: overlays, renders). Throws std::invalid_argument
  // as get(), and when the image is not of the calibration's size.
  cv::Mat rectifyLeft(const RawStereoCalibration& raw, const cv::Mat& left);
  std::size_t computed() const { return computed_; }  // maps computed so far (cache misses)

 private:
  std::size_t capacity_;
  std::size_t computed_ = 0;
  std::list<Rectification> entries_;  // most recently used first
};

}  // namespace nerv

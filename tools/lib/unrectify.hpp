// Raw views made from a rectified stereo pair: what an uncalibrated-looking rig with lens
// distortion and slightly rotated cameras would have captured of the same scene. Used to
// test rectification on ingest end to end on real frames (nerv_unrectify, the
// raw-frame integration test), where no raw recording with ground truth is at hand.
//
// The rig is built so that OpenCV's stereoRectify (Bouguet) brings it back to the
// original rectified orientation: the left camera is turned by Q^T and the right one by
// Q, so R = Q^2 and rectification turns each camera by half of R, i.e. by Q and Q^T,
// with the baseline already along x. The rectified pair the receiver computes then
// differs from the original only in its pinhole (focal length and principal point
// chosen by stereoRectify with alpha = 0): a scale and shift of the image, no rotation,
// the same camera centres, so depth, camera height and pitch are those of the original.
#pragma once

#include <opencv2/core.hpp>

#include <string>

#include "rectification.hpp"
#include "stereo_camera.hpp"

namespace nerv {

struct UnrectifyParams {
  double yaw_deg = 0.6;     // Q's rotation about the camera's y axis (each camera half of R's)
  double pitch_deg = 0.4;   // about x
  double roll_deg = 0.3;    // about z
  double left_k1 = -0.06, left_k2 = 0.012;    // radial distortion of the left lens
  double right_k1 = -0.05, right_k2 = 0.009;  // of the right lens
  double left_p1 = 4e-4, left_p2 = -3e-4;     // tangential distortion
  double right_p1 = -2e-4, right_p2 = 3e-4;
  double right_focal_scale = 1.004;  // the right lens' focal length against the left's
  double right_cx_shift_px = 2.5;    // its principal point against the left's
  double right_cy_shift_px = -1.5;
};

struct RawRig {
  RawStereoCalibration raw;   // the rig's calibration (what a stereo_calib run would give)
  cv::Matx33d Q;              // the rectifying rotation of the left camera (R1 of stereoRectify)
  StereoCamera rectified;     // the camera of the pair the receiver rectifies to
};

// The raw rig around the rectified camera `cam` (its fx, cy, baseline, size).
// Throws std::invalid_argument if the parameters give a rig that cannot be rectified.
RawRig makeRawRig(const StereoCamera& cam, const UnrectifyParams& p = {});

// The raw view of one camera: every raw pixel looks along the ray its lens gives it,
// and takes the rectified image's value where that ray lands (bilinear; rays outside
// the image take the nearest border pixel). `left` picks the camera.
cv::Mat unrectifyView(const cv::Mat& rectified, const StereoCamera& cam, const RawRig& rig, bool left);

// A point of the original rectified image in the receiver's rectified image.
cv::Point2d toReceiverRectified(const cv::Point2d& p, const StereoCamera& cam, const RawRig& rig);

// Writes `rig.raw` as an OpenCV stereo_calib file (M1 D1 M2 D2 R T, image_width/height),
// the format of a plain folder's raw_calib.yaml.
void writeOpenCvStereoCalibration(const std::string& path, const RawStereoCalibration& raw);

}  // namespace nerv

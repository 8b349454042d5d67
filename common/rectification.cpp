#include "rectification.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nerv {

std::string RawStereoCalibration::problem() const {
  std::ostringstream why;
  auto finite = [](const auto& a) {
    for (double v : a)
      if (!std::isfinite(v)) return false;
    return true;
  };
  if (width <= 0 || height <= 0)
    why << "raw image size " << width << "x" << height << " is not positive";
  else if (!finite(left_K) || !finite(right_K) || !finite(left_D) || !finite(right_D) ||
           !finite(R) || !finite(T))
    why << "raw calibration has a non-finite number";
  else if (left_K[0] <= 0 || left_K[4] <= 0 || right_K[0] <= 0 || right_K[4] <= 0 ||
           left_K[8] != 1.0 || right_K[8] != 1.0)
    why << "raw intrinsics need positive focal lengths and K[2][2] = 1";
  else if (std::hypot(T[0], T[1], T[2]) <= 0)
    why << "raw baseline T is zero";
  else {
    const cv::Matx33d r(R.data());
    if (cv::norm(r * r.t() - cv::Matx33d::eye()) > 1e-3 || cv::determinant(r) < 0)
      why << "raw R is not a rotation matrix";
  }
  return why.str();
}

bool RawStereoCalibration::operator==(const RawStereoCalibration& o) const {
  return width == o.width && height == o.height && left_K == o.left_K && left_D == o.left_D &&
         right_K == o.right_K && right_D == o.right_D && R == o.R && T == o.T;
}

Rectification computeRectification(const RawStereoCalibration& raw) {
  if (const std::string why = raw.problem(); !why.empty()) throw std::invalid_argument(why);
  Rectification r;
  r.raw = raw;
  const cv::Size size(raw.width, raw.height);
  const cv::Matx33d K1(raw.left_K.data()), K2(raw.right_K.data()), R(raw.R.data());
  const cv::Mat D1(1, 5, CV_64F, const_cast<double*>(raw.left_D.data()));
  const cv::Mat D2(1, 5, CV_64F, const_cast<double*>(raw.right_D.data()));
  const cv::Vec3d T(raw.T.data());
  cv::Mat Q;
  // Numbers that pass problem() can still defeat OpenCV (a baseline whose square
  // underflows) or give a camera no rig has: both are unusable calibrations.
  try {
    cv::stereoRectify(K1, D1, K2, D2, size, R, T, r.R1, r.R2, r.P1, r.P2, Q,
                      cv::CALIB_ZERO_DISPARITY, 0.0, size);
    cv::initUndistortRectifyMap(K1, D1, r.R1, r.P1, size, CV_16SC2, r.left_map1, r.left_map2);
    cv::initUndistortRectifyMap(K2, D2, r.R2, r.P2, size, CV_16SC2, r.right_map1, r.right_map2);
  } catch (const cv::Exception& e) {
    throw std::invalid_argument("raw calibration cannot be rectified: " + e.err);
  }
  // Horizontal rig: P2 = [f 0 cx f*Tx'; ...] with Tx' = -baseline in T's unit (m).
  r.camera.width = raw.width;
  r.camera.height = raw.height;
  r.camera.fx = r.P1.at<double>(0, 0);
  r.camera.fy = r.P1.at<double>(1, 1);
  r.camera.cx = r.P1.at<double>(0, 2);
  r.camera.cy = r.P1.at<double>(1, 2);
  r.camera.baseline_m = std::fabs(r.P2.at<double>(0, 3) / r.P2.at<double>(0, 0));
  if (const std::string why = r.camera.problem(); !why.empty())
    throw std::invalid_argument("rectified camera: " + why);
  return r;
}

const Rectification& Rectifier::get(const RawStereoCalibration& raw) {
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->raw == raw) {
      entries_.splice(entries_.begin(), entries_, it);
      return entries_.front();
    }
  entries_.push_front(computeRectification(raw));
  ++computed_;
  while (entries_.size() > capacity_) entries_.pop_back();
  return entries_.front();
}

const StereoCamera& Rectifier::rectify(const RawStereoCalibration& raw, const cv::Mat& left,
                                       const cv::Mat& right, cv::Mat& left_out,
                                       cv::Mat& right_out) {
  const Rectification& r = get(raw);
  cv::remap(left, left_out, r.left_map1, r.left_map2, cv::INTER_LINEAR);
  cv::remap(right, right_out, r.right_map1, r.right_map2, cv::INTER_LINEAR);
  return r.camera;
}

cv::Mat Rectifier::rectifyLeft(const RawStereoCalibration& raw, const cv::Mat& left) {
  const Rectification& r = get(raw);
  if (left.size() != r.left_map1.size()) throw std::invalid_argument("image size differs from the calibration's");
  cv::Mat out;
  cv::remap(left, out, r.left_map1, r.left_map2, cv::INTER_LINEAR);
  return out;
}

}  // namespace nerv

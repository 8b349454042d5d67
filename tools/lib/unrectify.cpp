#include "unrectify.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <stdexcept>

namespace nerv {
namespace {

cv::Matx33d rotationDeg(double pitch_deg, double yaw_deg, double roll_deg) {
  const double k = CV_PI / 180.0;
  const double a = pitch_deg * k, b = yaw_deg * k, c = roll_deg * k;
  const cv::Matx33d rx(1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a));
  const cv::Matx33d ry(std::cos(b), 0, std::sin(b), 0, 1, 0, -std::sin(b), 0, std::cos(b));
  const cv::Matx33d rz(std::cos(c), -std::sin(c), 0, std::sin(c), std::cos(c), 0, 0, 0, 1);
  return rx * ry * rz;
}

cv::Matx33d intrinsics(const StereoCamera& cam) {
  return cv::Matx33d(cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1);
}

}  // namespace

RawRig makeRawRig(const StereoCamera& cam, const UnrectifyParams& p) {
  if (const std::string why = cam.problem(); !why.empty()) throw std::invalid_argument("camera: " + why);
  RawRig rig;
  rig.Q = rotationDeg(p.pitch_deg, p.yaw_deg, p.roll_deg);
  RawStereoCalibration& raw = rig.raw;
  raw.width = cam.width;
  raw.height = cam.height;
  const cv::Matx33d K = intrinsics(cam);
  for (int i = 0; i < 9; ++i) raw.left_K[i] = K.val[i];
  const double s = p.right_focal_scale;
  const cv::Matx33d K2(cam.fx * s, 0, cam.cx + p.right_cx_shift_px, 0, cam.fy * s, cam.cy + p.right_cy_shift_px,
                       0, 0, 1);
  for (int i = 0; i < 9; ++i) raw.right_K[i] = K2.val[i];
  raw.left_D = {p.left_k1, p.left_k2, p.left_p1, p.left_p2, 0.0};
  raw.right_D = {p.right_k1, p.right_k2, p.right_p1, p.right_p2, 0.0};
  // Left camera X_l = Q^T X_o, right X_r = Q (X_o - (B, 0, 0)): X_r = Q^2 X_l - Q (B, 0, 0).
  const cv::Matx33d R = rig.Q * rig.Q;
  const cv::Vec3d T = -(rig.Q * cv::Vec3d(cam.baseline_m, 0, 0));
  for (int i = 0; i < 9; ++i) raw.R[i] = R.val[i];
  for (int i = 0; i < 3; ++i) raw.T[i] = T[i];

  const Rectification r = computeRectification(raw);  // throws for an unusable rig
  double off = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) off = std::max(off, std::fabs(r.R1.at<double>(i, j) - rig.Q(i, j)));
  if (off > 1e-9)
    throw std::invalid_argument("stereoRectify does not turn this rig back to the original orientation (" +
                                std::to_string(off) + "): use smaller rotations");
  rig.rectified = r.camera;
  return rig;
}

cv::Mat unrectifyView(const cv::Mat& rectified, const StereoCamera& cam, const RawRig& rig, bool left) {
  const cv::Size size(rig.raw.width, rig.raw.height);
  if (rectified.size() != size) throw std::invalid_argument("unrectifyView: image size differs from the rig's");
  const auto& Kv = left ? rig.raw.left_K : rig.raw.right_K;
  const auto& Dv = left ? rig.raw.left_D : rig.raw.right_D;
  const cv::Matx33d K(Kv.data());
  const cv::Mat D(1, 5, CV_64F, const_cast<double*>(Dv.data()));
  // The ray of a raw pixel in the original rectified camera: Q X for the left camera,
  // Q^T X for the right (makeRawRig).
  const cv::Matx33d to_rectified = left ? rig.Q : rig.Q.t();
  cv::Mat pixels(size.area(), 1, CV_64FC2);
  for (int y = 0, i = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x, ++i) pixels.at<cv::Vec2d>(i) = cv::Vec2d(x, y);
  cv::Mat landed;
  cv::undistortPoints(pixels, landed, K, D, to_rectified, intrinsics(cam),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 1e-10));
  cv::Mat map(size, CV_32FC2);
  for (int y = 0, i = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x, ++i) {
      const cv::Vec2d q = landed.at<cv::Vec2d>(i);
      map.at<cv::Vec2f>(y, x) = cv::Vec2f(static_cast<float>(q[0]), static_cast<float>(q[1]));
    }
  cv::Mat raw;
  cv::remap(rectified, raw, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return raw;
}

cv::Point2d toReceiverRectified(const cv::Point2d& p, const StereoCamera& cam, const RawRig& rig) {
  const StereoCamera& r = rig.rectified;
  return {r.cx + r.fx / cam.fx * (p.x - cam.cx), r.cy + r.fy / cam.fy * (p.y - cam.cy)};
}

void writeOpenCvStereoCalibration(const std::string& path, const RawStereoCalibration& raw) {
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  if (!fs.isOpened()) throw std::runtime_error("cannot write " + path);
  auto mat = [](const auto& a, int rows, int cols) {
    return cv::Mat(rows, cols, CV_64F, const_cast<double*>(a.data())).clone();
  };
  fs << "image_width" << raw.width << "image_height" << raw.height;
  fs << "M1" << mat(raw.left_K, 3, 3) << "D1" << mat(raw.left_D, 1, 5);
  fs << "M2" << mat(raw.right_K, 3, 3) << "D2" << mat(raw.right_D, 1, 5);
  fs << "R" << mat(raw.R, 3, 3) << "T" << mat(raw.T, 3, 1);
}

}  // namespace nerv

// Constructed disparity scenes and the real-frame loader shared by the
// test_snv_* and test_validator_* programs (header only: each test is its own program).
#pragma once

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "calibration_io.hpp"
#include "perception_types.hpp"
#include "stereo_camera.hpp"

namespace nerv::snv::test {

// KITTI 2011-09-26 colour camera geometry.
inline StereoCamera kittiCamera() {
  StereoCamera c;
  c.width = 1242;
  c.height = 375;
  c.fx = c.fy = 721.5377;
  c.cx = 609.5593;
  c.cy = 172.854;
  c.baseline_m = 0.5327;
  return c;
}

// Unit road normal (up) of a camera with this pitch (positive down) and roll
// (positive clockwise seen from behind): n ~ (-tan roll, -1, -tan pitch).
inline cv::Vec3d roadNormal(double pitch_deg, double roll_deg) {
  const double tp = std::tan(pitch_deg * CV_PI / 180), tr = std::tan(roll_deg * CV_PI / 180);
  return cv::normalize(cv::Vec3d(-tr, -1.0, -tp));
}

// Disparity of the plane n . P + h = 0 seen at pixel (u, v): from
// P = ((u-cx), (v-cy) fx/fy, fx) B/d:  d = -(B/h) (n_x (u-cx) + n_y (v-cy) fx/fy + n_z fx).
inline double planeDisparity(const StereoCamera& c, const cv::Vec3d& n, double h, double u,
                             double v) {
  return -(c.baseline_m / h) * (n[0] * (u - c.cx) + n[1] * (v - c.cy) * c.fx / c.fy + n[2] * c.fx);
}

// Analytic road: disparity of the ground plane where positive, 0 (invalid) above
// the horizon and below min_disparity.
inline cv::Mat roadDisparity(const StereoCamera& c, double pitch_deg, double roll_deg,
                             double height_m, double min_disparity = 1.0) {
  cv::Mat d(c.height, c.width, CV_32F);
  const cv::Vec3d n = roadNormal(pitch_deg, roll_deg);
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const double dv = planeDisparity(c, n, height_m, u, v);
      d.at<float>(v, u) = dv >= min_disparity ? static_cast<float>(dv) : 0.0f;
    }
  return d;
}

// v-disparity line of that road along the principal column (what stixel would fit).
inline GroundModel roadModel(const StereoCamera& c, double pitch_deg, double roll_deg,
                             double height_m) {
  const cv::Vec3d n = roadNormal(pitch_deg, roll_deg);
  GroundModel g;
  g.valid = true;
  g.source = "v_disparity";
  g.vd_slope = static_cast<float>(-(c.baseline_m / height_m) * n[1] * c.fx / c.fy);
  g.vd_intercept = static_cast<float>(planeDisparity(c, n, height_m, c.cx, 0.0));
  g.horizon_row = -g.vd_intercept / g.vd_slope;
  g.pitch_deg = static_cast<float>(pitch_deg);
  g.roll_deg = static_cast<float>(roll_deg);
  g.height_m = static_cast<float>(height_m);
  return g;
}

// Paints a vertical planar face into `d`: the face stands at base distance z_m,
// turned by yaw_deg about the vertical (0 = facing the camera), over the image box.
inline void paintUprightFace(cv::Mat& d, const StereoCamera& c, const cv::Rect& box, double z_m,
                             double yaw_deg) {
  // Face normal (toward the camera): (sin yaw, 0, -cos yaw); passes through (0, *, z_m) at u = cx.
  const double yaw = yaw_deg * CV_PI / 180;
  const cv::Vec3d n(std::sin(yaw), 0.0, -std::cos(yaw));
  const double h = -n.dot(cv::Vec3d(0, 0, z_m));  // n . P + h = 0 at P = (0, 0, z_m)
  for (int v = std::max(box.y, 0); v < std::min(box.y + box.height, d.rows); ++v)
    for (int u = std::max(box.x, 0); u < std::min(box.x + box.width, d.cols); ++u) {
      const double dv = planeDisparity(c, n, h, u, v);
      if (dv > 0) d.at<float>(v, u) = static_cast<float>(dv);
    }
}

inline std::string kittiSeqDir() { return std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq"; }

inline bool kittiSeqAvailable() {
  return std::filesystem::exists(kittiSeqDir() + "/calib.yaml") &&
         std::filesystem::exists(kittiSeqDir() + "/left/0000000000.png");
}

// SGBM as the brief fixes it: gray, 128 levels, block 5, P1 8*25, P2 32*25,
// MODE_SGBM_3WAY, fixed point / 16, negative -> 0 (invalid).
inline cv::Mat sgbmDisparity(const cv::Mat& left_bgr, const cv::Mat& right_bgr) {
  cv::Mat l, r;
  cv::cvtColor(left_bgr, l, cv::COLOR_BGR2GRAY);
  cv::cvtColor(right_bgr, r, cv::COLOR_BGR2GRAY);
  auto sgbm = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 0, 0, 0, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat raw, disp;
  sgbm->compute(l, r, raw);
  raw.convertTo(disp, CV_32F, 1.0 / 16.0);
  cv::threshold(disp, disp, 0.0, 0.0, cv::THRESH_TOZERO);
  return disp;
}

inline cv::Mat kittiSeqDisparity(int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%010d.png", frame);
  const cv::Mat l = cv::imread(kittiSeqDir() + "/left/" + name, cv::IMREAD_COLOR);
  const cv::Mat r = cv::imread(kittiSeqDir() + "/right/" + name, cv::IMREAD_COLOR);
  if (l.empty() || r.empty()) return cv::Mat();
  return sgbmDisparity(l, r);
}

}  // namespace nerv::snv::test

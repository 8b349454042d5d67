// Rectification on ingest: a pair rendered unrectified from a known calibration
// gives, after ingest, the disparity of the rectified render. Raw calibration loaders.
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <fstream>
#include <string>

#include "raw_calibration_io.hpp"
#include "rectification.hpp"
#include "stereo_matcher.hpp"

using namespace nerv;

namespace {

RawStereoCalibration testRig() {
  RawStereoCalibration c;
  c.width = 320;
  c.height = 240;
  c.left_K = {300, 0, 162, 0, 302, 118, 0, 0, 1};
  c.right_K = {305, 0, 158, 0, 304, 123, 0, 0, 1};
  c.left_D = {-0.12, 0.03, 0.001, -0.0015, 0};
  c.right_D = {-0.09, 0.02, -0.001, 0.001, 0};
  cv::Matx33d R;
  cv::Rodrigues(cv::Vec3d(0.01, -0.02, 0.008), R);
  for (int i = 0; i < 9; ++i) c.R[i] = R.val[i];
  c.T = {-0.25, 0.004, 0.003};  // right camera 25 cm to the right
  return c;
}

// raw(u, v) = rectified(rectifying map of (u, v)): the inverse of ingest's remap.
cv::Mat renderRaw(const cv::Mat& rectified, const cv::Matx33d& K, const std::array<double, 5>& D,
                  const cv::Mat& R, const cv::Mat& P) {
  std::vector<cv::Point2f> raw_pixels, rect_pixels;
  for (int v = 0; v < rectified.rows; ++v)
    for (int u = 0; u < rectified.cols; ++u) raw_pixels.emplace_back(u, v);
  cv::undistortPoints(raw_pixels, rect_pixels, K, cv::Mat(1, 5, CV_64F, const_cast<double*>(D.data())), R, P);
  cv::Mat map(rectified.size(), CV_32FC2, rect_pixels.data());
  cv::Mat raw;
  cv::remap(rectified, raw, map, cv::noArray(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return raw;
}

}  // namespace

TEST(stereoRectification, UnrectifiedRenderGivesTheRectifiedDisparity) {
  const RawStereoCalibration raw = testRig();
  const Rectification rect = computeRectification(raw);
  EXPECT_NEAR(rect.camera.baseline_m, std::sqrt(0.25 * 0.25 + 0.004 * 0.004 + 0.003 * 0.003), 1e-6);
  EXPECT_GT(rect.camera.fx, 200);

  // Rectified scene: a fronto-parallel textured plane at 14 px of disparity.
  cv::Mat noise(raw.height, raw.width + 64, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  const cv::Mat right_rect = noise(cv::Rect(32, 0, raw.width, raw.height)).clone();
  const cv::Mat left_rect = noise(cv::Rect(32 - 14, 0, raw.width, raw.height)).clone();

  const cv::Mat left_raw = renderRaw(left_rect, cv::Matx33d(raw.left_K.data()), raw.left_D, rect.R1, rect.P1);
  const cv::Mat right_raw = renderRaw(right_rect, cv::Matx33d(raw.right_K.data()), raw.right_D, rect.R2, rect.P2);
  ASSERT_GT(cv::norm(left_raw, left_rect, cv::NORM_L1) / left_raw.total(), 5.0) << "render is not distorted";

  Rectifier rectifier;
  cv::Mat left_in, right_in;
  const StereoCamera cam = rectifier.rectify(raw, left_raw, right_raw, left_in, right_in);
  EXPECT_DOUBLE_EQ(cam.fx, rect.camera.fx);
  rectifier.rectify(raw, left_raw, right_raw, left_in, right_in);
  EXPECT_EQ(rectifier.computed(), 1u) << "maps are cached per calibration";

  stereo::Params p;
  p.num_disparities = 32;
  auto matcher = stereo::StereoMatcher::create(p);
  cv::Mat expected, got;
  matcher->compute(left_rect, right_rect, expected);
  matcher->compute(left_in, right_in, got);
  const cv::Rect inner(40, 12, raw.width - 56, raw.height - 24);
  int both = 0, agree = 0;
  for (int y = inner.y; y < inner.br().y; ++y)
    for (int x = inner.x; x < inner.br().x; ++x) {
      const float a = expected.at<float>(y, x), b = got.at<float>(y, x);
      if (a <= 0 || b <= 0) continue;
      ++both;
      agree += std::abs(a - b) <= 0.5f;
    }
  EXPECT_GT(both, 0.8 * inner.area());
  EXPECT_GT(agree, 0.95 * both);

  // Without ingest the raw pair does not match well: the test is not vacuous.
  cv::Mat unrectified;
  matcher->compute(left_raw, right_raw, unrectified);
  int raw_agree = 0;
  for (int y = inner.y; y < inner.br().y; ++y)
    for (int x = inner.x; x < inner.br().x; ++x)
      raw_agree += std::abs(unrectified.at<float>(y, x) - expected.at<float>(y, x)) <= 0.5f;
  EXPECT_LT(raw_agree, 0.8 * both);
}

TEST(stereoRectification, CacheIsKeyedByCalibration) {
  Rectifier rectifier(2);
  RawStereoCalibration a = testRig(), b = testRig();
  b.T[0] = -0.3;
  rectifier.get(a);
  rectifier.get(b);
  rectifier.get(a);
  EXPECT_EQ(rectifier.computed(), 2u);
  EXPECT_NEAR(rectifier.get(b).camera.baseline_m, std::hypot(0.3, 0.004, 0.003), 1e-6);
  b.R[0] = 2.0;
  EXPECT_FALSE(b.problem().empty());
  EXPECT_THROW(rectifier.get(b), std::invalid_argument);
}

TEST(stereoRectification, KittiRawCalibrationComposesTheRelativePose) {
  const std::string path = testing::TempDir() + "/nerv_calib_cam_to_cam.txt";
  {
    std::ofstream f(path);
    f << "calib_time: 09-Jan-2012 13:57:47\ncorner_dist: 9.950000e-02\n";
    for (int cam : {0, 2, 3}) {
      cv::Matx33d R = cv::Matx33d::eye();
      cv::Vec3d T(0, 0, 0);
      if (cam == 2) { cv::Rodrigues(cv::Vec3d(0.01, 0.02, -0.01), R); T = {0.06, -0.001, 0.002}; }
      if (cam == 3) { cv::Rodrigues(cv::Vec3d(0.012, 0.018, -0.011), R); T = {-0.47, 0.004, -0.003}; }
      char id[4];
      std::snprintf(id, sizeof id, "%02d", cam);
      f << "S_" << id << ": 1.392000e+03 5.120000e+02\n";
      f << "K_" << id << ": 9.8e+02 0 6.9e+02 0 9.7e+02 2.4e+02 0 0 1\n";
      f << "D_" << id << ": -0.37 0.2 0.001 0.0012 -0.07\n";
      f << "R_" << id << ":";
      for (int i = 0; i < 9; ++i) f << " " << R.val[i];
      f << "\nT_" << id << ": " << T[0] << " " << T[1] << " " << T[2] << "\n";
    }
  }
  const RawStereoCalibration c = loadKittiRawStereoCalibration(path);
  EXPECT_EQ(c.width, 1392);
  EXPECT_EQ(c.height, 512);
  EXPECT_DOUBLE_EQ(c.left_D[0], -0.37);
  // A point in camera 0 maps to camera 3 both directly and through camera 2 + (R, T).
  cv::Matx33d R2, R3;
  cv::Rodrigues(cv::Vec3d(0.01, 0.02, -0.01), R2);
  cv::Rodrigues(cv::Vec3d(0.012, 0.018, -0.011), R3);
  const cv::Vec3d X0(1.0, -0.5, 12.0);
  const cv::Vec3d X2 = R2 * X0 + cv::Vec3d(0.06, -0.001, 0.002);
  const cv::Vec3d X3 = R3 * X0 + cv::Vec3d(-0.47, 0.004, -0.003);
  const cv::Vec3d via = cv::Matx33d(c.R.data()) * X2 + cv::Vec3d(c.T[0], c.T[1], c.T[2]);
  EXPECT_LT(cv::norm(via - X3), 1e-5);
  std::remove(path.c_str());
  EXPECT_THROW(loadKittiRawStereoCalibration(path), CalibrationError);
}

TEST(stereoRectification, OpenCvStereoCalibFile) {
  const RawStereoCalibration rig = testRig();
  for (const char* ext : {".yml", ".xml"}) {
    const std::string path = testing::TempDir() + "/nerv_stereo_calib" + ext;
    {
      cv::FileStorage fs(path, cv::FileStorage::WRITE);
      fs << "image_width" << rig.width << "image_height" << rig.height;
      fs << "M1" << cv::Mat(cv::Matx33d(rig.left_K.data())) << "D1" << cv::Mat(1, 5, CV_64F, const_cast<double*>(rig.left_D.data()));
      fs << "M2" << cv::Mat(cv::Matx33d(rig.right_K.data())) << "D2" << cv::Mat(1, 5, CV_64F, const_cast<double*>(rig.right_D.data()));
      fs << "R" << cv::Mat(cv::Matx33d(rig.R.data())) << "T" << cv::Mat(cv::Vec3d(rig.T[0], rig.T[1], rig.T[2]));
    }
    const RawStereoCalibration c = loadOpenCvStereoCalibration(path);
    EXPECT_TRUE(c == rig) << ext;
    std::remove(path.c_str());
  }
  EXPECT_THROW(loadOpenCvStereoCalibration("/nonexistent/stereo.yml"), CalibrationError);
}

// Raw views made from a rectified pair (tools/lib/unrectify.hpp) and raw folders
// (common/dataset.hpp, raw_calib.yaml): rectification on ingest must give the original
// pair back, scaled into the receiver's pinhole, and a raw folder must open as raw.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>

#include "dataset.hpp"
#include "frame_grid.hpp"
#include "message_convert.hpp"
#include "rectification.hpp"
#include "unrectify.hpp"

namespace fs = std::filesystem;
using namespace nerv;

namespace {

StereoCamera kittiLike() {
  StereoCamera c;
  c.width = 640;
  c.height = 200;
  c.fx = c.fy = 380.0;
  c.cx = 318.5;
  c.cy = 97.25;
  c.baseline_m = 0.54;
  return c;
}

// Smooth random texture: every pixel differs from its neighbours, slowly enough for
// bilinear sampling to be accurate to a fraction of a gray level.
cv::Mat texture(const cv::Size& size, int seed) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.5);
  cv::normalize(noise, noise, 20, 235, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

// Mean |rectified(q) - original(p(q))| over the inner part of the receiver's image, where
// p(q) is the original pixel the receiver's pixel q shows, shifted by `shift_px` (a control).
double meanError(const cv::Mat& rectified, const cv::Mat& original, const StereoCamera& cam, const RawRig& rig,
                 double shift_px) {
  const StereoCamera& r = rig.rectified;
  cv::Mat map(rectified.size(), CV_32FC2);
  for (int y = 0; y < map.rows; ++y)
    for (int x = 0; x < map.cols; ++x)
      map.at<cv::Vec2f>(y, x) = cv::Vec2f(static_cast<float>(cam.cx + (x - r.cx) * cam.fx / r.fx + shift_px),
                                          static_cast<float>(cam.cy + (y - r.cy) * cam.fy / r.fy));
  cv::Mat expected;
  cv::remap(original, expected, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  const cv::Rect inner(20, 12, rectified.cols - 40, rectified.rows - 24);
  cv::Mat diff;
  cv::absdiff(rectified(inner), expected(inner), diff);
  return cv::mean(diff)[0];
}

// openDataset(dir) must fail with a message containing `fragment`.
void expectDatasetError(const fs::path& dir, const std::string& fragment, const std::string& what) {
  try {
    openDataset(dir.string());
    ADD_FAILURE() << what << " opened";
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(toolsUnrectify, RigRectifiesBackToTheOriginalOrientationAndBaseline) {
  const StereoCamera cam = kittiLike();
  const RawRig rig = makeRawRig(cam);
  const Rectification r = computeRectification(rig.raw);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(r.R1.at<double>(i, j), rig.Q(i, j), 1e-9);
  EXPECT_NEAR(rig.rectified.baseline_m, cam.baseline_m, 1e-9);
  EXPECT_EQ(rig.rectified.width, cam.width);
  EXPECT_EQ(rig.rectified.height, cam.height);
  EXPECT_GT(rig.rectified.fx, cam.fx);  // alpha 0 crops the distorted border: a longer focal length
  EXPECT_LT(rig.rectified.fx, cam.fx * 1.1);
  // The rig is not a rectified one: the lenses distort and the cameras are turned.
  EXPECT_NE(rig.raw.left_D[0], 0.0);
  EXPECT_GT(std::fabs(rig.raw.R[1]), 1e-3);
}

TEST(toolsUnrectify, RectifyingTheRawViewsGivesTheOriginalPairBack) {
  const StereoCamera cam = kittiLike();
  const RawRig rig = makeRawRig(cam);
  const cv::Mat left = texture({cam.width, cam.height}, 1), right = texture({cam.width, cam.height}, 2);
  const cv::Mat raw_left = unrectifyView(left, cam, rig, true);
  const cv::Mat raw_right = unrectifyView(right, cam, rig, false);
  // The raw views really are distorted: compared pixel by pixel they are far from the originals.
  cv::Mat d;
  cv::absdiff(raw_left, left, d);
  EXPECT_GT(cv::mean(d)[0], 10.0);

  Rectifier rectifier;
  cv::Mat left_rect, right_rect;
  const StereoCamera& got = rectifier.rectify(rig.raw, raw_left, raw_right, left_rect, right_rect);
  EXPECT_NEAR(got.fx, rig.rectified.fx, 1e-9);
  EXPECT_NEAR(got.cx, rig.rectified.cx, 1e-9);
  EXPECT_NEAR(got.cy, rig.rectified.cy, 1e-9);
  // Measured: 0.45 gray levels per view (two bilinear samplings), 5.4 one pixel off.
  const double left_error = meanError(left_rect, left, cam, rig, 0.0);
  const double right_error = meanError(right_rect, right, cam, rig, 0.0);
  const double shifted = meanError(left_rect, left, cam, rig, 1.0);  // one pixel off
  EXPECT_LT(left_error, 1.0) << "left view";
  EXPECT_LT(right_error, 1.0) << "right view";
  EXPECT_GT(shifted, 5.0 * left_error) << "the comparison must see a one-pixel error";
}

TEST(toolsUnrectify, LabelPointsMoveWithTheReceiversPinhole) {
  const StereoCamera cam = kittiLike();
  const RawRig rig = makeRawRig(cam);
  const cv::Point2d centre = toReceiverRectified({cam.cx, cam.cy}, cam, rig);
  EXPECT_NEAR(centre.x, rig.rectified.cx, 1e-9);
  EXPECT_NEAR(centre.y, rig.rectified.cy, 1e-9);
  const cv::Point2d right = toReceiverRectified({cam.cx + 100, cam.cy}, cam, rig);
  EXPECT_NEAR(right.x - centre.x, 100 * rig.rectified.fx / cam.fx, 1e-9);
}

TEST(commonDatasetRaw, PlainFolderWithRawCalibrationOpensAsRaw) {
  const fs::path dir = fs::temp_directory_path() / ("nerv_unrectify_" + std::to_string(::getpid()));
  fs::create_directories(dir / "left");
  fs::create_directories(dir / "right");
  const StereoCamera cam = kittiLike();
  const RawRig rig = makeRawRig(cam);
  cv::imwrite((dir / "left" / "000000.png").string(), texture({cam.width, cam.height}, 3));
  cv::imwrite((dir / "right" / "000000.png").string(), texture({cam.width, cam.height}, 4));
  writeOpenCvStereoCalibration((dir / "raw_calib.yaml").string(), rig.raw);

  const Dataset ds = openDataset(dir.string());
  ASSERT_EQ(ds.frames.size(), 1u);
  const DatasetFrame& f = ds.frames.front();
  ASSERT_TRUE(f.raw.has_value());
  EXPECT_TRUE(*f.raw == rig.raw);
  EXPECT_NEAR(f.camera.fx, rig.rectified.fx, 1e-9);
  EXPECT_NEAR(f.camera.baseline_m, cam.baseline_m, 1e-9);

  // What nerv_source sends: the raw block, rectified = false, and a usable first block.
  const stereo_calibration_t msg = toCalibration(*f.raw, f.camera);
  EXPECT_FALSE(msg.rectified);
  EXPECT_TRUE(toRawCalibration(msg) == rig.raw);
  EXPECT_EQ(toCamera(msg).problem(), "");

  // Both calibrations: which one describes the images is unclear, so it is an error.
  std::ofstream(dir / "calib.yaml") << "width: 640\nheight: 200\nfx: 380\nfy: 380\ncx: 318.5\ncy: 97.25\nbaseline_m: 0.54\n";
  expectDatasetError(dir, "both calib.yaml", "a folder with both calibrations");
  fs::remove(dir / "calib.yaml");

  // A rig calibrated for another image size than the images'.
  RawStereoCalibration other = rig.raw;
  other.width = 1242;
  other.height = 375;
  writeOpenCvStereoCalibration((dir / "raw_calib.yaml").string(), other);
  expectDatasetError(dir, "is for 1242x375 images", "a calibration for 1242x375 with 640x200 images");
  fs::remove_all(dir);
}

// KITTI's unrectified downloads: image_02/data at the cameras' size S_02 are raw views.
TEST(commonDatasetRaw, KittiExtractFolderOpensAsRaw) {
  const fs::path dir = fs::temp_directory_path() / ("nerv_extract_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "image_02" / "data");
  fs::create_directories(dir / "image_03" / "data");
  {
    std::ofstream f(dir / "calib_cam_to_cam.txt");
    f << "calib_time: 09-Jan-2012 13:57:47\n";
    for (int cam : {0, 2, 3}) {
      char id[4];
      std::snprintf(id, sizeof id, "%02d", cam);
      const double tx = cam == 2 ? 0.06 : cam == 3 ? -0.47 : 0.0;
      f << "S_" << id << ": 3.200000e+02 1.200000e+02\n";
      f << "K_" << id << ": 2.4e+02 0 1.6e+02 0 2.4e+02 6.0e+01 0 0 1\n";
      f << "D_" << id << ": -0.1 0.02 0.0 0.0 0.0\n";
      f << "R_" << id << ": 1 0 0 0 1 0 0 0 1\n";
      f << "T_" << id << ": " << tx << " 0 0\n";
      f << "S_rect_" << id << ": 3.000000e+02 1.000000e+02\n";
      f << "P_rect_" << id << ": 2.3e+02 0 1.5e+02 " << tx * 230 << " 0 2.3e+02 5.0e+01 0 0 0 1 0\n";
    }
  }
  auto images = [&](int w, int h) {
    const cv::Mat img = texture({w, h}, 5);
    cv::imwrite((dir / "image_02" / "data" / "0000000000.png").string(), img);
    cv::imwrite((dir / "image_03" / "data" / "0000000000.png").string(), img);
  };
  images(300, 100);  // the rectified size: rectified views, as before
  Dataset ds = openDataset(dir.string());
  EXPECT_EQ(ds.layout, "kitti_raw");
  EXPECT_FALSE(ds.frames.front().raw.has_value());
  EXPECT_EQ(ds.frames.front().camera.width, 300);

  images(320, 120);  // the raw size: raw views with cameras 2 and 3's calibration
  ds = openDataset(dir.string());
  ASSERT_TRUE(ds.frames.front().raw.has_value());
  EXPECT_EQ(ds.frames.front().raw->width, 320);
  EXPECT_DOUBLE_EQ(ds.frames.front().raw->left_D[0], -0.1);
  EXPECT_NEAR(ds.frames.front().camera.baseline_m, 0.53, 1e-9);
  EXPECT_EQ(ds.frames.front().camera.width, 320);

  images(200, 80);  // neither
  expectDatasetError(dir, "neither the rectified size 300x100", "200x80 images with a 300x100 / 320x120 calibration");
  fs::remove_all(dir);
}

// nerv_render / nerv_report draw on the left view of STEREO_FRAME: a raw view is rectified
// first, as the stereo_matcher does, so boxes in the rectified frame land on their objects.
TEST(toolsUnrectify, RenderedLeftViewOfARawFrameIsRectified) {
  const StereoCamera cam = kittiLike();
  const RawRig rig = makeRawRig(cam);
  const cv::Mat raw_left = unrectifyView(texture({cam.width, cam.height}, 6), cam, rig, true);
  LogFrame frame;
  frame.stereo = stereo_frame_t{};
  frame.stereo->calib = toCalibration(rig.raw, rig.rectified);
  frame.stereo->left = encodeImage(raw_left, "gray8");
  std::string problem;
  const cv::Mat shown = viz::leftImage(frame, &problem);
  ASSERT_FALSE(shown.empty()) << problem;
  Rectifier rectifier;
  cv::Mat expected, unused;
  rectifier.rectify(rig.raw, raw_left, raw_left, expected, unused);
  cv::Mat gray;
  cv::cvtColor(shown, gray, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::norm(gray, expected, cv::NORM_INF), 0.0);

  frame.stereo->calib.R[0] = 2.0;  // not a rotation: said, not drawn raw
  EXPECT_TRUE(viz::leftImage(frame, &problem).empty());
  EXPECT_NE(problem.find("cannot be rectified"), std::string::npos) << problem;

  frame.stereo->calib = toCalibration(rig.rectified);  // a rectified frame: shown as it is
  const cv::Mat as_is = viz::leftImage(frame, &problem);
  cv::cvtColor(as_is, gray, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::norm(gray, raw_left, cv::NORM_INF), 0.0);
}

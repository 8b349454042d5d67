// Ground line fit, line <-> pose geometry and the explicit "no ground" cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "ground_geometry.hpp"
#include "ground_line_fit.hpp"
#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"
#include "v_disparity.hpp"

namespace nerv::stixel {
namespace {

// The line formulas against ray casting: the disparity the renderer produces for
// road pixels must be a*v + b with a, b from groundLineFromPose, and the pose
// recovered from (a, b) must be the one rendered.
TEST(stixelGroundGeometry, LineFormulasMatchRayCastRoad) {
  StereoCamera cam = kittiLikeCamera();
  for (float pitch : {-4.0f, -0.5f, 0.0f, 1.5f, 6.0f})
    for (float height : {0.8f, 1.65f, 3.0f}) {
      RoadScene scene;
      scene.camera_height_m = height;
      scene.pitch_deg = pitch;
      const cv::Mat disp = renderDisparity(scene, cam);
      float a, b;
      groundLineFromPose(pitch, height, cam, a, b);
      for (int v = 0; v < cam.height; v += 7) {
        const float d = disp.at<float>(v, 400);
        if (d <= 0) continue;
        EXPECT_NEAR(d, a * v + b, 1e-3 * std::max(1.0f, d)) << "pitch " << pitch << " h " << height;
      }
      const LinePose pose = poseFromGroundLine(a, b, cam);
      EXPECT_NEAR(pose.pitch_deg, pitch, 1e-3);
      EXPECT_NEAR(pose.height_m, height, 1e-4);
      // The horizon is the row of a level ray: cy - fy*tan(pitch).
      EXPECT_NEAR(pose.horizon_row, cam.cy - cam.fy * std::tan(pitch * M_PI / 180.0), 1e-2);
    }
}

TEST(stixelGroundGeometry, BriefFormulasHoldForSquarePixels) {
  // tilt = atan((a*cy + b)/(fx*a)), height = B*cos(tilt)/a when fy = fx.
  const StereoCamera cam = kittiLikeCamera();
  const float a = 0.3253f, b = -57.30f;
  const LinePose p = poseFromGroundLine(a, b, cam);
  const double tilt = std::atan((a * cam.cy + b) / (cam.fx * a));
  EXPECT_NEAR(p.pitch_deg, tilt * 180 / M_PI, 1e-4);
  EXPECT_NEAR(p.height_m, cam.baseline_m * std::cos(tilt) / a, 1e-5);
}

TEST(stixelGroundGeometry, NonSquarePixelsUseFy) {
  StereoCamera cam = kittiLikeCamera();
  cam.fy = 700.0;
  RoadScene scene;
  scene.pitch_deg = 2.0f;
  scene.camera_height_m = 1.4f;
  const cv::Mat disp = renderDisparity(scene, cam);
  // Two road rows fix the line; the pose must come back.
  const int v1 = 250, v2 = 350;
  const float d1 = disp.at<float>(v1, 600), d2 = disp.at<float>(v2, 600);
  const float a = (d2 - d1) / (v2 - v1), b = d1 - a * v1;
  const LinePose p = poseFromGroundLine(a, b, cam);
  EXPECT_NEAR(p.pitch_deg, 2.0, 1e-3);
  EXPECT_NEAR(p.height_m, 1.4, 1e-3);
}

TEST(stixelGroundGeometry, HeightAboveGroundOfABoxTop) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.pitch_deg = 1.0f;
  scene.boxes.push_back({12.0f, -1.0f, 1.0f, 1.2f});
  const cv::Mat disp = renderDisparity(scene, cam);
  float a, b;
  groundLineFromPose(scene.pitch_deg, scene.camera_height_m, cam, a, b);
  const GroundModel g = groundModelFromLine(a, b, cam, "test");
  // Highest row of the box at the image centre column: above it the road is
  // farther away, so its disparity is clearly smaller.
  const float d_box = static_cast<float>(cam.disparityFromDepth(12.0));
  int top = -1;
  for (int v = 0; v < cam.height && top < 0; ++v)
    if (disp.at<float>(v, 610) > 0.9f * d_box) top = v;
  ASSERT_GE(top, 0);
  EXPECT_NEAR(heightAboveGround(g, top, disp.at<float>(top, 610)), 1.2, 0.03);
}

// Synthetic disparity of a pitched road where 30 % of the pixels are replaced by
// outliers (uniform random disparities and a block of far-too-near values).
TEST(stixelGroundLineFit, RecoversLineWithThirtyPercentOutliers) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.pitch_deg = 1.2f;
  scene.camera_height_m = 1.5f;
  cv::Mat disp = renderDisparity(scene, cam);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f), any_d(0.5f, 120.0f);
  int replaced = 0, total = 0;
  for (int v = 0; v < disp.rows; ++v)
    for (int u = 0; u < disp.cols; ++u) {
      float& d = disp.at<float>(v, u);
      if (d <= 0) continue;
      ++total;
      if (uni(rng) < 0.3f) {
        d = any_d(rng);
        ++replaced;
      }
      d += 0.2f * (uni(rng) - 0.5f);  // matcher noise
    }
  ASSERT_NEAR(double(replaced) / total, 0.3, 0.01);
  float a, b;
  groundLineFromPose(scene.pitch_deg, scene.camera_height_m, cam, a, b);
  const GroundLine line = fitGroundLine(computeVDisparity(disp, 256.0f), cam, GroundLineFitParams{});
  ASSERT_TRUE(line.ok) << line.reason;
  EXPECT_NEAR(line.slope, a, 0.01 * std::abs(a));
  EXPECT_NEAR(line.intercept, b, 0.01 * std::abs(b));
  const LinePose p = poseFromGroundLine(line.slope, line.intercept, cam);
  EXPECT_NEAR(p.height_m, 1.5, 0.03);
  EXPECT_NEAR(p.pitch_deg, 1.2, 0.1);
}

TEST(stixelGroundLineFit, CellsJustAboveTheRoadDoNotTiltTheLine) {
  // The feet of obstacles, kerbs and the road beside them put pixels a little
  // nearer than the road in many rows (here a third of every lower row, 1.2 px
  // above the road: inside the 1.5 px inlier band). Nothing lies below the road.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.pitch_deg = 0.5f;
  cv::Mat disp = renderDisparity(scene, cam);
  for (int v = disp.rows / 2; v < disp.rows; ++v)
    for (int u = 0; u < disp.cols; u += 3)
      if (disp.at<float>(v, u) > 0) disp.at<float>(v, u) += 1.2f;
  const VDisparity vd = computeVDisparity(disp, 256.0f);
  auto fit = [&](float above_px) {
    GroundLineFitParams p;
    p.obstacle_side_tolerance_px = above_px;
    const GroundLine line = fitGroundLine(vd, cam, p);
    EXPECT_TRUE(line.ok) << line.reason;
    return poseFromGroundLine(line.slope, line.intercept, cam);
  };
  const LinePose tight = fit(1.0f), symmetric = fit(0.0f);
  EXPECT_NEAR(tight.pitch_deg, 0.5, 0.05);
  EXPECT_NEAR(tight.height_m, 1.65, 0.01);
  EXPECT_GT(std::abs(symmetric.pitch_deg - 0.5), 2 * std::abs(tight.pitch_deg - 0.5) + 0.03)
      << "the symmetric band takes the near cells in (pitch " << symmetric.pitch_deg << " deg, height "
      << symmetric.height_m << " m; tight " << tight.pitch_deg << " deg, " << tight.height_m << " m)";
}

TEST(stixelGroundLineFit, RecoversLineBehindLargeObstacles) {
  // Upright obstacles are vertical segments in v-disparity; they must not tilt the line.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.pitch_deg = -0.5f;
  scene.boxes = {{6.0f, -3.0f, 0.5f, 2.0f}, {15.0f, 0.5f, 6.0f, 3.0f}};
  const cv::Mat disp = renderDisparity(scene, cam);
  const StixelResult r = estimateStixels(disp, cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  EXPECT_EQ(r.ground.source, "v_disparity");
  EXPECT_NEAR(r.ground.height_m, 1.65, 0.02);
  EXPECT_NEAR(r.ground.pitch_deg, -0.5, 0.1);
}

TEST(stixelGroundLineFit, RejectsImpossibleCameraHeight) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.camera_height_m = 6.0f;  // above max_camera_height_m = 4
  const cv::Mat disp = renderDisparity(scene, cam);
  const StixelResult r = estimateStixels(disp, cam, Params{});
  EXPECT_FALSE(r.ground.valid);
  EXPECT_EQ(r.ground.source, "none");
  EXPECT_TRUE(r.stixels.empty());
  EXPECT_TRUE(r.hypotheses.empty());
}

TEST(stixelNoGround, AllInvalidDisparityGivesExplicitInvalidGround) {
  const StereoCamera cam = kittiLikeCamera();
  const cv::Mat disp(cam.height, cam.width, CV_32F, cv::Scalar(0));
  const StixelResult r = estimateStixels(disp, cam, Params{});
  EXPECT_FALSE(r.ground.valid);
  EXPECT_EQ(r.ground.source, "none");
  EXPECT_TRUE(r.stixels.empty());
  EXPECT_TRUE(r.hypotheses.empty());
}

TEST(stixelNoGround, FrontoParallelWallGivesInvalidGroundOrThePrior) {
  const StereoCamera cam = kittiLikeCamera();
  const cv::Mat wall(cam.height, cam.width, CV_32F, cv::Scalar(cam.disparityFromDepth(8.0)));
  const StixelResult r = estimateStixels(wall, cam, Params{});
  EXPECT_FALSE(r.ground.valid);
  EXPECT_EQ(r.ground.source, "none");
  EXPECT_TRUE(r.stixels.empty());

  // With a prior the road comes from the extrinsics, never from the wall.
  GroundPrior prior;
  prior.valid = true;
  prior.pitch_deg = 0.5f;
  prior.height_m = 1.6f;
  const StixelResult rp = estimateStixels(wall, cam, Params{}, prior);
  ASSERT_TRUE(rp.ground.valid);
  EXPECT_EQ(rp.ground.source, "extrinsics_prior");
  EXPECT_NEAR(rp.ground.height_m, 1.6, 1e-4);
  EXPECT_NEAR(rp.ground.pitch_deg, 0.5, 1e-4);

  // A prior no vehicle camera can have is ignored like a bad fit.
  GroundPrior broken = prior;
  broken.height_m = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(estimateStixels(wall, cam, Params{}, broken).ground.valid);
  broken = prior;
  broken.pitch_deg = 30.0f;
  EXPECT_FALSE(estimateStixels(wall, cam, Params{}, broken).ground.valid);

  // ...and so is every prior when it is switched off.
  Params no_prior;
  no_prior.use_extrinsics_prior = false;
  EXPECT_FALSE(estimateStixels(wall, cam, no_prior, prior).ground.valid);
}

TEST(stixelNoGround, NanAndInfDisparitiesAreInvalidPixels) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.boxes.push_back({15.0f, -1.0f, 1.0f, 1.5f});
  cv::Mat disp = renderDisparity(scene, cam);
  std::mt19937 rng(3);
  const float specials[] = {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(), -5.0f, 1e30f};
  for (int i = 0; i < 40000; ++i)
    disp.at<float>(rng() % disp.rows, rng() % disp.cols) = specials[rng() % 5];
  const StixelResult r = estimateStixels(disp, cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  EXPECT_NEAR(r.ground.height_m, 1.65, 0.03);
  for (const Stixel& s : r.stixels) {
    EXPECT_TRUE(std::isfinite(s.disparity) && std::isfinite(s.depth_m));
    EXPECT_TRUE(std::isfinite(s.base_x_m) && std::isfinite(s.base_z_m));
  }
  ASSERT_EQ(r.hypotheses.size(), 1u);
  EXPECT_NEAR(r.hypotheses[0].z_m, 15.0, 0.45);

  // Entirely non-finite input: no ground, no crash.
  cv::Mat nan(cam.height, cam.width, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(estimateStixels(nan, cam, Params{}).ground.valid);
}

TEST(stixelNoGround, BadInputIsRejectedWithAMessage) {
  const StereoCamera cam = kittiLikeCamera();
  EXPECT_THROW(estimateStixels(cv::Mat(cam.height, cam.width, CV_16S), cam, Params{}),
               std::invalid_argument);
  EXPECT_THROW(estimateStixels(cv::Mat(10, 10, CV_32F, cv::Scalar(1)), cam, Params{}),
               std::invalid_argument);
  EXPECT_FALSE(estimateStixels(cv::Mat(), cam, Params{}).ground.valid);
}

}  // namespace
}  // namespace nerv::stixel

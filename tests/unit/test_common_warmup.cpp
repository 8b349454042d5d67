// The warm-up frames of the services (warmup_frame.hpp): sizes and contents,
// the stixel stage finds their road and box, and a warm-up changes no result:
// the matcher and snv_extrinsic give a later frame the same output as a fresh
// instance does (snv after resetFilter).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"
#include "warmup_frame.hpp"

using namespace nerv;

TEST(commonWarmup, ThePairHasTheSizeAndTheRightViewIsTheLeftShifted) {
  cv::Mat left, right;
  warmupPair({320, 96}, left, right);
  ASSERT_EQ(left.size(), cv::Size(320, 96));
  ASSERT_EQ(right.size(), left.size());
  EXPECT_EQ(left.type(), CV_8U);
  EXPECT_EQ(cv::norm(left.colRange(16, 320), right.colRange(0, 304), cv::NORM_INF), 0.0);
  cv::Scalar mean, stddev;
  cv::meanStdDev(left, mean, stddev);
  EXPECT_GT(stddev[0], 20.0) << "the census needs texture";
  cv::Mat again, unused;
  warmupPair({320, 96}, again, unused);
  EXPECT_EQ(cv::norm(left, again, cv::NORM_INF), 0.0) << "the same frame at every start";
}

TEST(commonWarmup, TheDisparityIsTheRoadOfItsGroundModelWithABoxOn) {
  const StereoCamera cam = warmupCamera({1242, 375});
  EXPECT_TRUE(cam.problem().empty()) << cam.problem();
  const cv::Mat d = warmupDisparity(cam);
  ASSERT_EQ(d.size(), cv::Size(1242, 375));
  ASSERT_EQ(d.type(), CV_32F);
  const GroundModel g = warmupGround(cam);
  for (const int v : {250, 300, 374})
    EXPECT_NEAR(d.at<float>(v, 20), g.groundDisparity(static_cast<float>(v)), 1e-3) << "row " << v;
  const std::vector<Hypothesis> hs = warmupHypotheses(cam);
  ASSERT_EQ(hs.size(), 1u);
  const Box& b = hs[0].box;
  EXPECT_NEAR(d.at<float>(b.y + b.h / 2, b.x + b.w / 2), cam.disparityFromDepth(15.0), 1e-3);
  EXPECT_NEAR(d.at<float>(10, 20), cam.disparityFromDepth(40.0), 1e-3);
}

TEST(commonWarmup, TheStixelStageFindsItsRoadAndItsBox) {
  for (const WarmupSize size : {WarmupSize{1242, 375}, WarmupSize{2048, 1024}, WarmupSize{1280, 720}}) {
    const StereoCamera cam = warmupCamera(size);
    const stixel::StixelResult r = stixel::estimateStixels(warmupDisparity(cam), cam, stixel::Params{});
    ASSERT_TRUE(r.ground.valid) << size.width;
    EXPECT_NEAR(r.ground.height_m, 1.65, 0.05) << size.width;
    bool box = false;
    for (const Hypothesis& h : r.hypotheses) box = box || std::abs(h.z_m - 15.0f) < 1.0f;
    EXPECT_TRUE(box) << size.width << ": the warm-up runs the grouping too";
  }
}

TEST(commonWarmup, TheMatcherGivesTheNextFrameWhatAFreshOneGives) {
  const std::string dir = std::string(NERV_SHARED_DATA) + "/kitti2015_000005";
  cv::Mat left = cv::imread(dir + "/left/000005_10.png", cv::IMREAD_GRAYSCALE);
  cv::Mat right = cv::imread(dir + "/right/000005_10.png", cv::IMREAD_GRAYSCALE);
  if (left.empty() || right.empty()) {  // no KITTI here: a rendered road of the same size
    const StereoCamera cam = stixel::kittiLikeCamera();
    warmupPair({cam.width, cam.height}, left, right);
    cv::flip(left, left, 1);
    cv::flip(right, right, 1);
  }
  stereo::Params p;
  p.threads = 2;
  cv::Mat fresh, fresh_conf, warm, warm_conf, wl, wr;
  stereo::StereoMatcher::create(p)->compute(left, right, fresh, fresh_conf);
  auto matcher = stereo::StereoMatcher::create(p);
  warmupPair({left.cols, left.rows}, wl, wr);
  matcher->compute(wl, wr, warm, warm_conf);
  matcher->compute(left, right, warm, warm_conf);
  EXPECT_EQ(cv::norm(fresh, warm, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(fresh_conf, warm_conf, cv::NORM_INF), 0.0);
}

TEST(commonWarmup, SnvAfterWarmUpAndResetEstimatesAsAFreshEstimator) {
  // A pitched road seen by the KITTI-like camera, two frames.
  const StereoCamera cam = stixel::kittiLikeCamera();
  stixel::RoadScene scene;
  scene.pitch_deg = 1.0f;
  scene.boxes = {{12.0f, -1.0f, 1.0f, 1.5f}};
  const cv::Mat d = stixel::renderDisparity(scene, cam);
  const stixel::StixelResult st = stixel::estimateStixels(d, cam, stixel::Params{});
  ASSERT_TRUE(st.ground.valid);

  snv::SnvExtrinsicEstimator fresh{snv::Params{}}, warmed{snv::Params{}};
  const StereoCamera wcam = warmupCamera({cam.width, cam.height});
  warmed.process(warmupDisparity(wcam), wcam, warmupHypotheses(wcam), warmupGround(wcam));
  warmed.resetFilter();
  for (int frame = 0; frame < 2; ++frame) {
    const snv::SnvResult a = fresh.process(d, cam, st.hypotheses, st.ground);
    const snv::SnvResult b = warmed.process(d, cam, st.hypotheses, st.ground);
    ASSERT_TRUE(a.pose.valid);
    EXPECT_EQ(a.pose.pitch_deg, b.pose.pitch_deg) << "frame " << frame;
    EXPECT_EQ(a.pose.roll_deg, b.pose.roll_deg) << "frame " << frame;
    EXPECT_EQ(a.pose.height_m, b.pose.height_m) << "frame " << frame;
    EXPECT_EQ(a.pose.filter_pitch_var, b.pose.filter_pitch_var) << "frame " << frame;
    ASSERT_EQ(a.rois.size(), b.rois.size());
    for (size_t i = 0; i < a.rois.size(); ++i) EXPECT_EQ(a.rois[i].num_normals, b.rois[i].num_normals);
  }
  // Without the reset the warm-up frame's pose stays in the filter.
  snv::SnvExtrinsicEstimator unreset{snv::Params{}};
  unreset.process(warmupDisparity(wcam), wcam, warmupHypotheses(wcam), warmupGround(wcam));
  snv::SnvExtrinsicEstimator fresh2{snv::Params{}};
  const snv::SnvResult c = fresh2.process(d, cam, st.hypotheses, st.ground);
  const snv::SnvResult u = unreset.process(d, cam, st.hypotheses, st.ground);
  EXPECT_NE(c.pose.pitch_deg, u.pose.pitch_deg);
}

// Per-ROI normal statistics on constructed scenes: a box standing on the road,
// a road-only patch, a fronto-parallel noise patch, and degenerate ROIs.
#include <gtest/gtest.h>

#include "roi_normal_stats.hpp"
#include "snv_extrinsic.hpp"
#include "snv_test_scenes.hpp"

namespace nerv::snv {
namespace {

Hypothesis roi(int id, int x, int y, int w, int h) {
  Hypothesis r;
  r.id = id;
  r.box = {x, y, w, h};
  return r;
}

void print(const char* what, const NormalStats& s) {
  std::printf("%-14s samples %4d normals %4d density %.2f ground %.2f object %.2f error %.2f "
              "normal (%.2f %.2f %.2f) pitch %.1f yaw %.1f tilt %.1f\n",
              what, s.num_samples, s.num_normals, s.density, s.ground_fraction, s.object_fraction,
              s.error_fraction, s.normal[0], s.normal[1], s.normal[2], s.pitch_deg, s.yaw_deg,
              s.tilt_from_ground_deg);
}

class snvRoiScene : public ::testing::Test {
 protected:
  void SetUp() override {
    cam = test::kittiCamera();
    disparity = test::roadDisparity(cam, 0.0, 0.0, 1.65);
    // A 1.5 m high box 12 m ahead, its base on the road (rows 182..272): its
    // rear faces the camera, its right side is turned 60 deg and visible.
    test::paintUprightFace(disparity, cam, cv::Rect(555, 182, 108, 90), 12.0, 0.0);
    test::paintUprightFace(disparity, cam, cv::Rect(663, 182, 40, 90), 12.0, 60.0);
    // A fronto-parallel blob of constant disparity 20 px with matching noise,
    // like SGBM paints over a textureless patch.
    cv::Mat blob(100, 150, CV_32F);
    cv::randn(blob, 20.0, 0.05);
    blob.copyTo(disparity(cv::Rect(250, 150, 150, 100)));
  }
  StereoCamera cam;
  cv::Mat disparity;
};

TEST_F(snvRoiScene, BoxRoadAndNoisePatchGetTheirClasses) {
  SnvExtrinsicEstimator est{Params{}};
  const std::vector<Hypothesis> rois = {roi(7, 555, 182, 148, 90), roi(3, 800, 260, 200, 80),
                                        roi(11, 260, 160, 130, 80)};
  const SnvResult r = est.process(disparity, cam, rois, GroundModel{});
  ASSERT_TRUE(r.pose.valid);
  ASSERT_EQ(r.rois.size(), 3u);
  const NormalStats &box = r.rois[0], &road = r.rois[1], &noise = r.rois[2];
  print("box", box);
  print("road", road);
  print("noise patch", noise);
  EXPECT_EQ(box.roi_id, 7);
  EXPECT_EQ(road.roi_id, 3);
  EXPECT_EQ(noise.roi_id, 11);
  for (const NormalStats* s : {&box, &road, &noise}) {
    EXPECT_GT(s->num_normals, 200);
    EXPECT_GT(s->density, 0.6f);
    EXPECT_LE(s->ground_fraction + s->object_fraction + s->error_fraction, 1.0f + 1e-6f);
  }
  EXPECT_GT(box.object_fraction, 0.7f);
  EXPECT_LT(box.ground_fraction, 0.1f);
  EXPECT_EQ(box.error_fraction, 0.0f);
  EXPECT_NEAR(box.tilt_from_ground_deg, 90.0f, 5.0f);

  EXPECT_GT(road.ground_fraction, 0.95f);
  EXPECT_LT(road.object_fraction, 0.05f);
  EXPECT_NEAR(road.tilt_from_ground_deg, 0.0f, 1.0f);
  EXPECT_NEAR(road.normal[1], -1.0f, 1e-3f);

  EXPECT_GT(noise.error_fraction, 0.8f);
  EXPECT_LT(noise.object_fraction, 0.15f);
  EXPECT_NEAR(noise.pitch_deg, 90.0f, 10.0f);  // representative normal faces the camera
}

TEST_F(snvRoiScene, TurnedFaceGivesYawAndElevation) {
  std::vector<LocalNormal> normals;
  IntegralNormalField field;
  field.prepare(disparity, cam, IntegralNormalParams{});
  const int samples = localNormalsInRect(field, cv::Rect(667, 190, 32, 70), 4, normals);
  const NormalStats s = computeRoiStats(1, samples, normals, cv::Vec3f(0, -1, 0), RoiStatsParams{});
  print("side face", s);
  EXPECT_NEAR(s.yaw_deg, 60.0f, 1.0f);
  EXPECT_NEAR(s.pitch_deg, 30.0f, 1.0f);  // elevation from the image plane: asin(cos 60)
  EXPECT_NEAR(s.object_fraction, 1.0f, 1e-6);
}

TEST_F(snvRoiScene, DegenerateRoisGiveExplicitEmptyStats) {
  SnvExtrinsicEstimator est{Params{}};
  const std::vector<Hypothesis> rois = {roi(1, 2000, 100, 50, 50),  // right of the image
                                        roi(2, -300, -200, 100, 100),  // above-left
                                        roi(3, 400, 200, 0, 40),       // empty
                                        roi(4, 500, 200, -20, -20),    // negative size
                                        roi(5, 1200, 350, 200, 200)};  // partly outside
  const SnvResult r = est.process(disparity, cam, rois, GroundModel{});
  ASSERT_EQ(r.rois.size(), rois.size());
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(r.rois[i].roi_id, rois[i].id);
    EXPECT_EQ(r.rois[i].num_samples, 0);
    EXPECT_EQ(r.rois[i].num_normals, 0);
    EXPECT_EQ(r.rois[i].density, 0.0f);
    EXPECT_EQ(r.rois[i].ground_fraction + r.rois[i].object_fraction + r.rois[i].error_fraction, 0.0f);
  }
  // Only the part inside the image is sampled: columns 1200..1240, rows 352..372.
  EXPECT_EQ(r.rois[4].num_samples, 11 * 6);
}

TEST(snvRoiStats, AllInvalidDisparity) {
  const StereoCamera cam = test::kittiCamera();
  SnvExtrinsicEstimator est{Params{}};
  const cv::Mat d(cam.height, cam.width, CV_32F, cv::Scalar(0.0f));
  const SnvResult r = est.process(d, cam, {roi(9, 100, 100, 80, 80)}, GroundModel{});
  EXPECT_FALSE(r.pose.valid);
  EXPECT_EQ(r.pose.status, "no_ground");
  ASSERT_EQ(r.rois.size(), 1u);
  EXPECT_EQ(r.rois[0].num_samples, 20 * 20);
  EXPECT_EQ(r.rois[0].num_normals, 0);
  EXPECT_EQ(r.rois[0].density, 0.0f);
  EXPECT_EQ(r.rois[0].normal[0] * r.rois[0].normal[0] + r.rois[0].normal[1] * r.rois[0].normal[1] +
                r.rois[0].normal[2] * r.rois[0].normal[2],
            0.0f);
}

}  // namespace
}  // namespace nerv::snv

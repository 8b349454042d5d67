// End to end, in-process: the rendered `alongside` scene (config/scenes/alongside.yaml),
// a van and a car driving beside the camera car, seen mostly from their sides, through
// nerv_sgm -> stixels -> SNV -> validator. A vehicle's side recedes along the road
// like a guard rail; the low-run rule (low_runs.hpp) must keep it by its height. Both
// must be detected and kept in every frame where they are mostly in view.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "dataset.hpp"
#include "detection_eval.hpp"
#include "kitti_labels.hpp"
#include "scene_yaml.hpp"
#include "sequence.hpp"
#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "validator.hpp"

using namespace nerv;
namespace fs = std::filesystem;

TEST(qualityAlongside, VehiclesBesideTheCameraCarAreDetectedAndKept) {
  const fs::path dir = fs::temp_directory_path() / ("nerv_quality_alongside_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const int kFrames = 3;
  synth::RenderOptions ro;
  ro.supersample = 1;
  synth::writeSequence(synth::loadScene(std::string(NERV_SOURCE_DIR) + "/config/scenes/alongside.yaml"), kFrames,
                       dir.string(), ro);
  const Dataset ds = openDataset(dir.string());
  ASSERT_EQ(static_cast<int>(ds.frames.size()), kFrames);
  auto matcher = stereo::StereoMatcher::create(stereo::Params{});
  snv::SnvExtrinsicEstimator snv_est(snv::Params{});
  stixel::GroundPrior prior;
  int beside = 0, kept = 0;
  for (const DatasetFrame& f : ds.frames) {
    cv::Mat disparity;
    matcher->compute(cv::imread(f.left_path, cv::IMREAD_GRAYSCALE), cv::imread(f.right_path, cv::IMREAD_GRAYSCALE),
                     disparity);
    const stixel::StixelResult st = stixel::estimateStixels(disparity, f.camera, stixel::Params{}, prior);
    ASSERT_TRUE(st.ground.valid) << f.name;
    const snv::SnvResult sn = snv_est.process(disparity, f.camera, st.hypotheses, st.ground);
    if (sn.pose.valid && sn.pose.confidence >= 0.3f) prior = {true, sn.pose.pitch_deg, sn.pose.roll_deg, sn.pose.height_m};
    const std::vector<Verdict> verdicts = validator::validate(st.hypotheses, sn.rois, validator::Params{});
    for (const KittiLabel& l : readKittiLabels(f.label_path)) {
      // the two placed beside the camera car: one lane left or right, less than 12 m ahead
      if ((l.type != "Van" && l.type != "Car") || std::abs(std::abs(l.x) - 3.75f) > 0.3f || l.z > 12.0f) continue;
      if (l.truncated >= 0.5f) continue;  // mostly out of view
      ++beside;
      bool found = false;
      for (size_t i = 0; i < st.hypotheses.size(); ++i) {
        const Box& b = st.hypotheses[i].box;
        const EvalBox hb{float(b.x), float(b.y), float(b.x + b.w), float(b.y + b.h), 0, 0};
        if (iou(hb, labelBox(l)) > 0.5f && verdicts[i].kept) found = true;
      }
      kept += found;
      EXPECT_TRUE(found) << f.name << ": the " << l.type << " beside the camera car (x " << l.x << " m, z " << l.z
                         << " m) has no kept box";
    }
  }
  std::printf("alongside: %d of %d vehicle views beside the camera car detected and kept\n", kept, beside);
  EXPECT_EQ(beside, 2 * kFrames);  // the van and the car in every frame
  fs::remove_all(dir);
}

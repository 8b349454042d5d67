// The generator's output on disk: KITTI object layout readable by
// nerv::openDataset, calibration, disparity encoding, labels and trap masks.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>

#include "dataset.hpp"
#include "kitti_writer.hpp"
#include "scene_yaml.hpp"
#include "sequence.hpp"

namespace {

using namespace nerv::synth;
namespace fs = std::filesystem;

TEST(synthOutput, OpenDatasetReadsTheSequenceAndItsCalibration) {
  SceneSpec spec = loadScene(resolveScenePath("wet_road", NERV_SOURCE_DIR "/config/scenes"));
  resizeImage(spec, 414, 125);
  const std::string dir = (fs::temp_directory_path() / "nerv_test_synth_output").string();
  fs::remove_all(dir);
  const SequenceSummary summary = writeSequence(spec, 3, dir);
  EXPECT_EQ(summary.frames, 3);

  const nerv::Dataset ds = nerv::openDataset(dir);
  EXPECT_EQ(ds.layout, "kitti_object");
  ASSERT_EQ(ds.frames.size(), 3u);
  const nerv::StereoCamera& want = spec.camera.intrinsics;
  SceneSequence seq(spec);
  for (size_t i = 0; i < ds.frames.size(); ++i) {
    const nerv::DatasetFrame& f = ds.frames[i];
    EXPECT_EQ(f.name, frameName(static_cast<int>(i)));
    EXPECT_EQ(f.camera.width, 414);
    EXPECT_EQ(f.camera.height, 125);
    EXPECT_NEAR(f.camera.fx, want.fx, 1e-9);
    EXPECT_NEAR(f.camera.fy, want.fy, 1e-9);
    EXPECT_NEAR(f.camera.cx, want.cx, 1e-9);
    EXPECT_NEAR(f.camera.cy, want.cy, 1e-9);
    EXPECT_NEAR(f.camera.baseline_m, want.baseline_m, 1e-9);
    ASSERT_FALSE(f.label_path.empty());
    ASSERT_FALSE(f.disp_gt_path.empty());

    // Disparity PNG: uint16 = d * 256, 0 where there is none (the sky).
    const SynthFrame r = seq.render(static_cast<int>(i));
    const cv::Mat disp = cv::imread(f.disp_gt_path, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(disp.type(), CV_16U);
    int sky = 0;
    for (int v = 0; v < disp.rows; ++v)
      for (int u = 0; u < disp.cols; ++u) {
        const float gt = r.images.disparity.at<float>(v, u);
        EXPECT_NEAR(disp.at<uint16_t>(v, u) / 256.0, gt, 0.5 / 256 + 1e-6);
        sky += gt == 0;
      }
    EXPECT_GT(sky, 0);
    EXPECT_EQ(cv::norm(cv::imread(f.left_path), r.images.left, cv::NORM_INF), 0);

    // Trap mask: 8-bit, 0/255, non-empty on the wet road.
    const cv::Mat mask = cv::imread(dir + "/trap_mask/" + f.name + ".png", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_8U);
    EXPECT_EQ(cv::countNonZero(mask), cv::countNonZero(r.images.trap_mask));
    EXPECT_GT(cv::countNonZero(mask), 0);

    // Labels: 15 KITTI fields; objects have a 3D size, DontCare has not.
    std::ifstream labels(f.label_path);
    std::string line;
    int objects = 0;
    while (std::getline(labels, line)) {
      std::istringstream fields(line);
      std::string type;
      double v[14];
      fields >> type;
      for (double& x : v) ASSERT_TRUE(fields >> x) << line;
      EXPECT_LE(v[3], v[5]);  // left <= right
      EXPECT_LE(v[4], v[6]);  // top <= bottom
      if (type != "DontCare") {
        ++objects;
        EXPECT_GT(v[7], 0);   // height
        EXPECT_GT(v[12], 0);  // z in front of the camera
      }
    }
    EXPECT_GT(objects, 3);
  }
  // Calibration file: KITTI P0..P3 with P3[0][3] = -fx B relative to P2.
  std::ifstream calib(dir + "/calib/000000.txt");
  std::string line;
  std::map<std::string, std::vector<double>> rows;
  while (std::getline(calib, line)) {
    std::istringstream in(line.substr(line.find(':') + 1));
    double x;
    while (in >> x) rows[line.substr(0, line.find(':'))].push_back(x);
  }
  for (const char* p : {"P0", "P1", "P2", "P3"}) ASSERT_EQ(rows[p].size(), 12u) << p;
  EXPECT_NEAR(rows["P2"][3] - rows["P3"][3], want.fx * want.baseline_m, 1e-6);
  EXPECT_EQ(rows["R0_rect"].size(), 9u);
  fs::remove_all(dir);
}

}  // namespace

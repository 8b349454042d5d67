// Camera presets config/cameras/*.yaml: every service accepts them
// (--check-config on the real binaries, and readParams in-process), and the
// stixel stage with the preset's parameters finds the road and a box in an
// exact disparity rendered for that camera.
#include <gtest/gtest.h>

#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "config.hpp"
#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"
#include "validator.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

struct Preset {
  const char* file;
  StereoCamera cam;
  float camera_height_m;
};

StereoCamera camera(int w, int h, double f, double baseline) {
  StereoCamera c;
  c.width = w;
  c.height = h;
  c.fx = c.fy = f;
  c.cx = w / 2.0 - 0.5;
  c.cy = h / 2.0 - 0.5;
  c.baseline_m = baseline;
  return c;
}

const Preset kPresets[] = {
    {"kitti.yaml", camera(1242, 375, 721.5377, 0.5327), 1.65f},
    {"cityscapes.yaml", camera(2048, 1024, 2263.5, 0.209), 1.22f},
    {"zed.yaml", camera(1280, 720, 700.0, 0.12), 1.0f},
};

std::string presetPath(const char* file) { return std::string(NERV_SOURCE_DIR) + "/config/cameras/" + file; }

// build/tests/test_x -> build/bin
fs::path binDir() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) return {};
  buf[n] = 0;
  return fs::path(buf).parent_path().parent_path() / "bin";
}

}  // namespace

class qualityPresets : public ::testing::TestWithParam<Preset> {};

TEST_P(qualityPresets, EveryServiceReadsThePreset) {
  const YAML::Node root = loadConfigFile(presetPath(GetParam().file));
  ConfigSection top(root, "");
  for (const char* k : {"lcm_url", "channel_prefix", "limits", "source", "run"}) top.allow(k);
  ConfigSection st = top.section("stereo_matcher");
  EXPECT_NO_THROW(stereo::readParams(st));
  for (const char* k : {"output_encoding", "queue"}) st.allow(k);
  EXPECT_NO_THROW(st.finish());
  ConfigSection sx = top.section("stixel");
  EXPECT_NO_THROW(stixel::readParams(sx));
  for (const char* k : {"queue", "min_prior_confidence"}) sx.allow(k);
  EXPECT_NO_THROW(sx.finish());
  ConfigSection sn = top.section("snv_extrinsic");
  EXPECT_NO_THROW(snv::readParams(sn));
  for (const char* k : {"queue", "join_capacity", "join_timeout_ms"}) sn.allow(k);
  EXPECT_NO_THROW(sn.finish());
  ConfigSection va = top.section("validator");
  EXPECT_NO_THROW(validator::readParams(va));
  for (const char* k : {"queue", "join_capacity", "join_timeout_ms"}) va.allow(k);
  EXPECT_NO_THROW(va.finish());
  EXPECT_NO_THROW(top.finish());
}

TEST_P(qualityPresets, ServicesAcceptItWithCheckConfig) {
  const fs::path bin = binDir();
  int checked = 0;
  for (const char* s : {"stereo_matcher", "stixel", "snv_extrinsic", "validator"}) {
    if (!fs::exists(bin / s)) continue;
    const std::string cmd = (bin / s).string() + " --config " + presetPath(GetParam().file) +
                            " --check-config > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "services not built in " << bin;
}

TEST_P(qualityPresets, StixelsFindRoadAndBoxForThatCamera) {
  const Preset& preset = GetParam();
  const YAML::Node root = loadConfigFile(presetPath(preset.file));
  ConfigSection top(root, "");
  ConfigSection sx = top.section("stixel");
  const stixel::Params params = stixel::readParams(sx);
  stixel::RoadScene scene;
  scene.camera_height_m = preset.camera_height_m;
  scene.pitch_deg = 0.5f;
  scene.boxes = {{15.0f, -1.0f, 1.0f, 1.5f}};
  const cv::Mat disparity = stixel::renderDisparity(scene, preset.cam);
  const stixel::StixelResult r = stixel::estimateStixels(disparity, preset.cam, params);
  ASSERT_TRUE(r.ground.valid) << preset.file;
  EXPECT_NEAR(r.ground.height_m, preset.camera_height_m, 0.05) << preset.file;
  EXPECT_NEAR(r.ground.pitch_deg, 0.5, 0.3) << preset.file;
  ASSERT_EQ(r.hypotheses.size(), 1u) << preset.file;
  EXPECT_NEAR(r.hypotheses[0].z_m, 15.0, 0.75) << preset.file;
  EXPECT_NEAR(r.hypotheses[0].width_m, 2.0, 0.3) << preset.file;
}

INSTANTIATE_TEST_SUITE_P(qualityCameras, qualityPresets, ::testing::ValuesIn(kPresets),
                         [](const ::testing::TestParamInfo<Preset>& i) {
                           std::string n = i.param.file;
                           return n.substr(0, n.find('.'));
                         });

// Camera presets config/cameras/*.yaml: every service accepts them
// (--check-config on the real binaries, and readParams in-process), and the
// stixel stage with the preset's parameters finds the road and a box in an
// exact disparity rendered for that camera. qualityServiceKeys.*: the keys a service's
// main reads besides its algorithm's parameters (pipeline_keys.hpp) are accepted
// by its --check-config, and the in-process tools accept the pipeline config and
// the presets the services run with.
#include <gtest/gtest.h>

#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <fstream>
#include <string>

#include "config.hpp"
#include "pipeline_keys.hpp"
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

// A valid value for each service-only key, as YAML.
const std::map<std::string, std::string> kValues = {
    {"shard", "{count: 1, index: 0}"},   {"queue", "3"},
    {"output_encoding", "png16"},       {"publish_confidence", "false"},
    {"row_check_every_frames", "5"},   {"max_row_offset_px", "0.3"},
    {"row_correction", "false"},        {"row_correction_above_px", "0.3"}, {"max_row_correction_px", "2"},
    {"offset_correction", "false"},     {"max_offset_correction_px", "2"}, {"max_view_delay_ms", "3"}, {"max_disparity_offset_px", "0.4"},
    {"rig_state_file", "/tmp/nerv_rig_state_unused.yaml"},
    {"min_prior_confidence", "0.4"},    {"max_prior_age_frames", "20"},
    {"max_prior_age_ms", "2000"},
    {"max_unobserved_fraction", "0.5"}, {"join_capacity", "6"},
    {"join_timeout_ms", "1500"}};

const char* const kServices[] = {"stereo_matcher", "stixel", "snv_extrinsic", "validator"};

int checkConfig(const fs::path& binary, const std::string& yaml) {
  const fs::path file = fs::temp_directory_path() / ("nerv_keys_" + std::to_string(getpid()) + ".yaml");
  std::ofstream(file) << yaml;
  const std::string cmd = binary.string() + " --config " + file.string() + " --check-config > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  fs::remove(file);
  return rc;
}

}  // namespace

class qualityPresets : public ::testing::TestWithParam<Preset> {};

TEST_P(qualityPresets, EveryServiceReadsThePreset) {
  const YAML::Node root = loadConfigFile(presetPath(GetParam().file));
  ConfigSection top(root, "");
  allowPipelineTopLevelKeys(top);
  ConfigSection st = top.section("stereo_matcher");
  EXPECT_NO_THROW(stereo::readParams(st));
  allowServiceOnlyKeys(st, "stereo_matcher");
  EXPECT_NO_THROW(st.finish());
  ConfigSection sx = top.section("stixel");
  EXPECT_NO_THROW(stixel::readParams(sx));
  allowServiceOnlyKeys(sx, "stixel");
  EXPECT_NO_THROW(sx.finish());
  ConfigSection sn = top.section("snv_extrinsic");
  EXPECT_NO_THROW(snv::readParams(sn));
  allowServiceOnlyKeys(sn, "snv_extrinsic");
  EXPECT_NO_THROW(sn.finish());
  ConfigSection va = top.section("validator");
  EXPECT_NO_THROW(validator::readParams(va));
  allowServiceOnlyKeys(va, "validator");
  EXPECT_NO_THROW(va.finish());
  EXPECT_NO_THROW(top.finish());
}

TEST_P(qualityPresets, ServicesAcceptItWithCheckConfig) {
  const fs::path bin = binDir();
  int checked = 0;
  for (const char* s : kServices) {
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

TEST(qualityServiceKeys, EveryServiceAcceptsEveryKeyListedForIt) {
  const fs::path bin = binDir();
  int checked = 0;
  for (const char* service : kServices) {
    if (!fs::exists(bin / service)) continue;
    std::string yaml = std::string(service) + ":\n";
    for (const std::string& key : nerv::serviceOnlyKeys(service)) {
      ASSERT_TRUE(kValues.count(key)) << "no test value for " << service << "." << key;
      yaml += "  " + key + ": " + kValues.at(key) + "\n";
    }
    EXPECT_EQ(checkConfig(bin / service, yaml), 0) << yaml;
    // The check is live: a key nobody reads is refused.
    EXPECT_NE(checkConfig(bin / service, yaml + "  not_a_key: 1\n"), 0) << service;
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "services not built in " << bin;
}

TEST(qualityServiceKeys, InProcessToolsAcceptThePipelineConfigAndTheCameraPresets) {
  const fs::path bin = binDir();
  const std::string data = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  const std::string disparity = std::string(NERV_SHARED_DATA) + "/kitti2015_000005";
  if (!fs::exists(bin / "bench_detection") || !fs::exists(bin / "nerv_eval_disparity"))
    GTEST_SKIP() << "tools not built in " << bin;
  if (!fs::is_directory(data) || !fs::is_directory(disparity)) GTEST_SKIP() << "no KITTI data in " << NERV_SHARED_DATA;
  const std::string root = NERV_SOURCE_DIR;
  const fs::path cache = fs::temp_directory_path() / ("nerv_keys_cache_" + std::to_string(getpid()));
  for (const std::string& config : {root + "/config/pipeline.yaml", root + "/config/cameras/kitti.yaml",
                                   root + "/config/cameras/cityscapes.yaml", root + "/config/cameras/zed.yaml"}) {
    const std::string detect = (bin / "bench_detection").string() + " --data " + data + " --frames 1 --quiet --cache " +
                               cache.string() + " --config " + config + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(detect.c_str()), 0) << detect;
    const std::string eval = (bin / "nerv_eval_disparity").string() + " --data " + disparity + " --config " + config +
                             " > /dev/null 2>&1";
    EXPECT_EQ(std::system(eval.c_str()), 0) << eval;
  }
  fs::remove_all(cache);
}

TEST(qualityServiceKeys, AnUnknownServiceHasOnlyItsShard) {
  EXPECT_EQ(nerv::serviceOnlyKeys("source"), std::vector<std::string>{"shard"});
}

TEST(qualityServiceKeys, TheWarmUpSizeIsBothOrNeither) {
  const fs::path bin = binDir();
  int checked = 0;
  for (const char* service : kServices) {
    if (!fs::exists(bin / service)) continue;
    EXPECT_EQ(checkConfig(bin / service, "warmup:\n  width: 1242\n  height: 375\n"), 0) << service;
    EXPECT_EQ(checkConfig(bin / service, "warmup: {}\n"), 0) << service << ": no size, no warm-up";
    EXPECT_NE(checkConfig(bin / service, "warmup:\n  width: 1242\n"), 0) << service;
    EXPECT_NE(checkConfig(bin / service, "warmup:\n  width: 1242\n  height: -1\n"), 0) << service;
    EXPECT_NE(checkConfig(bin / service, "warmup:\n  width: 1242\n  height: 375\n  depth: 3\n"), 0) << service;
    EXPECT_NE(checkConfig(bin / service, "limits: {max_width: 1000, max_height: 1000}\nwarmup: {width: 1242, height: 375}\n"),
              0) << service << ": a warm-up larger than the limits accept";
    EXPECT_NE(checkConfig(bin / service, "warmup: {width: 1, height: 1}\n"), 0) << service << ": below 16 x 16";
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "services not built in " << bin;
}

TEST(qualityServiceKeys, TheMatcherSearchesNoFurtherThanTheWireCarries) {
  // DISPARITY holds 1/256 px in 16 bits: a search beyond 256 px would publish nearer surfaces
  // at 255.996 px, too far, silently. The service refuses it at start (the tools in-process
  // may search further, with no wire between).
  const fs::path service = binDir() / "stereo_matcher";
  if (!fs::exists(service)) GTEST_SKIP() << "stereo_matcher not built in " << binDir();
  EXPECT_EQ(checkConfig(service, "stereo_matcher: {num_disparities: 256}\n"), 0);
  EXPECT_EQ(checkConfig(service, "stereo_matcher: {num_disparities: 224, min_disparity: 32}\n"), 0);
  EXPECT_NE(checkConfig(service, "stereo_matcher: {num_disparities: 320}\n"), 0);
  EXPECT_NE(checkConfig(service, "stereo_matcher: {num_disparities: 240, min_disparity: 32}\n"), 0);
  ConfigSection c(YAML::Load("{num_disparities: 320}"), "stereo_matcher");
  EXPECT_NO_THROW(stereo::readParams(c));  // in-process: allowed
}

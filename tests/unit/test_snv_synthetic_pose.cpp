// Super-SNV camera pose on rendered synthetic sequences with exact pose ground
// truth (nerv_synth in-process: render -> SGBM as in the brief -> process()).
// Targets (issue 6): |pitch error| and |roll error| <= 0.1 deg at the 95th
// percentile, height within 2 cm; the entropy lower on clean than on trapped frames.
// MEASURED (docs/snv.md, instant pose, SGBM): roll p95 0.015-0.034 deg (target MET,
// from the robust road plane), height within 2 cm (met: 0.7-1.3 cm), pitch p95 0.036 deg
// on pitch_oscillation and 0.071 on urban (target MET, pitch from the second plane fit on
// the super-SNV window's samples; it was 0.179 on pitch_oscillation with the mean shift);
// entropy of the plane residuals lower on urban than on wet_road (met, means).
// With the lowest-surface selection (planes and height without raised sidewalks):
// SGBM pitch_oscillation 0.031 / 0.034 deg / 0.8 cm, urban 0.068 / 0.020 / 0.7 cm,
// wet_road 0.034 / 0.021 / 0.6 cm; entropy means urban 2.81, wet_road 3.11 bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "camera_pose.hpp"
#include "config.hpp"
#include "renderer.hpp"
#include "scene_yaml.hpp"
#include "snv_extrinsic.hpp"
#include "snv_test_scenes.hpp"
#include "stereo_matcher.hpp"
#include "world_builder.hpp"

namespace nerv::snv {
namespace {

struct FrameResult {
  double pitch_err_deg, roll_err_deg, height_err_m, entropy_bits;
  double pub_pitch_err_deg, pub_roll_err_deg, pub_height_err_m;  // published (filtered) pose
  double trap_share;  // share of ground-region grid pixels inside a trap
  bool valid;
};

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * v.size())) - 1)];
}

// Renders `frames` frames of a preset (every `stride`-th), runs SGBM (block 5,
// P1 200, P2 800, 128 levels, /16) and the estimator (no stixel ground model),
// and compares with the rig's exact pose.
// matcher "sgbm": the SGBM above; any other name: stereo::StereoMatcher with
// its defaults (the pipeline's matcher, "nerv_sgm").
// camera_config: a camera preset (config/cameras/NAME.yaml) whose stereo_matcher and
// snv_extrinsic sections replace the defaults; `adjust` changes the scene (its rig).
std::vector<FrameResult> runScene(const std::string& preset, int frames, int stride,
                                  const std::string& matcher = "sgbm", const std::string& camera_config = "",
                                  const std::function<void(synth::SceneSpec&)>& adjust = {}) {
  stereo::Params sp;
  Params snv_params;
  if (!camera_config.empty()) {
    ConfigSection root(loadConfigFile(std::string(NERV_SOURCE_DIR) + "/config/cameras/" + camera_config + ".yaml"), "");
    ConfigSection stereo_section = root.section("stereo_matcher");
    sp = stereo::readParams(stereo_section);
    ConfigSection snv_section = root.section("snv_extrinsic");
    snv_params = readParams(snv_section);
  }
  std::unique_ptr<stereo::StereoMatcher> own;
  if (matcher != "sgbm") {
    sp.algorithm = matcher;
    own = stereo::StereoMatcher::create(sp);
  }
  synth::SceneSpec spec =
      synth::loadScene(synth::resolveScenePath(preset, std::string(NERV_SOURCE_DIR) + "/config/scenes"));
  if (adjust) adjust(spec);
  const synth::World world = synth::buildWorld(spec);
  const StereoCamera& cam = spec.camera.intrinsics;
  SnvExtrinsicEstimator est{snv_params};
  std::vector<FrameResult> out;
  for (int k = 0; k < frames; ++k) {
    const int f = k * stride;
    const synth::CameraPose pose = synth::cameraPose(spec.camera, world, f);
    const synth::RenderedFrame rf = synth::renderFrame(world, spec.camera, pose, f, spec.seed);
    cv::Mat d;
    if (own) {
      cv::Mat l, r;
      cv::cvtColor(rf.left, l, cv::COLOR_BGR2GRAY);
      cv::cvtColor(rf.right, r, cv::COLOR_BGR2GRAY);
      own->compute(l, r, d);
    } else {
      d = test::sgbmDisparity(rf.left, rf.right);
    }
    const SnvResult r = est.process(d, cam, {}, GroundModel{});
    FrameResult fr{};
    fr.valid = r.pose.valid;
    fr.pitch_err_deg = r.pose.instant_pitch_deg - pose.pitch_deg;
    fr.roll_err_deg = r.pose.instant_roll_deg - pose.roll_deg;
    fr.height_err_m = r.pose.instant_height_m - pose.height_m;
    fr.entropy_bits = r.pose.entropy;
    fr.pub_pitch_err_deg = r.pose.pitch_deg - pose.pitch_deg;
    fr.pub_roll_err_deg = r.pose.roll_deg - pose.roll_deg;
    fr.pub_height_err_m = r.pose.height_m - pose.height_m;
    int in_region = 0, trapped = 0;
    for (int v = static_cast<int>(cam.cy) + 10; v < cam.height; v += 4)
      for (int u = 0; u < cam.width; u += 4) {
        ++in_region;
        trapped += rf.trap_mask.at<uchar>(v, u) != 0;
      }
    fr.trap_share = double(trapped) / in_region;
    std::printf("%-8s %-17s frame %3d: true pitch %6.3f roll %6.3f h %.3f | err pitch %+.3f roll %+.3f "
                "h %+.3f m | published %+.3f %+.3f %+.3f | H %.2f bits conf %.2f samples %d traps %.1f%% %s\n",
                matcher.c_str(), preset.c_str(), f, pose.pitch_deg, pose.roll_deg, pose.height_m, fr.pitch_err_deg,
                fr.roll_err_deg, fr.height_err_m, fr.pub_pitch_err_deg, fr.pub_roll_err_deg, fr.pub_height_err_m, r.pose.entropy, r.pose.confidence, r.ground_samples,
                100 * fr.trap_share, r.pose.status.c_str());
    out.push_back(fr);
  }
  return out;
}

struct Summary {
  double pitch95, roll95, height95, entropy_mean;
  double pub_pitch95, pub_roll95, pub_height95;  // published (filtered) pose
};

Summary summarise(const std::string& name, const std::vector<FrameResult>& res) {
  std::vector<double> p, r, h, e, pp, pr, ph;
  for (const FrameResult& f : res) {
    EXPECT_TRUE(f.valid) << name;
    p.push_back(std::abs(f.pitch_err_deg));
    r.push_back(std::abs(f.roll_err_deg));
    h.push_back(std::abs(f.height_err_m));
    e.push_back(f.entropy_bits);
    pp.push_back(std::abs(f.pub_pitch_err_deg));
    pr.push_back(std::abs(f.pub_roll_err_deg));
    ph.push_back(std::abs(f.pub_height_err_m));
  }
  const Summary s{percentile(p, 0.95),  percentile(r, 0.95),  percentile(h, 0.95),
                  std::accumulate(e.begin(), e.end(), 0.0) / e.size(),
                  percentile(pp, 0.95), percentile(pr, 0.95), percentile(ph, 0.95)};
  std::printf("%s: |pitch err| p95 %.3f deg, |roll err| p95 %.3f deg, |height err| p95 %.3f m, "
              "mean entropy %.2f bits\n",
              name.c_str(), s.pitch95, s.roll95, s.height95, s.entropy_mean);
  std::printf("%s published (filtered): |pitch err| p95 %.3f deg, |roll err| p95 %.3f deg, "
              "|height err| p95 %.3f m; entropy min %.2f max %.2f\n",
              name.c_str(), s.pub_pitch95, s.pub_roll95, s.pub_height95,
              *std::min_element(e.begin(), e.end()), *std::max_element(e.begin(), e.end()));
  ::testing::Test::RecordProperty(name + "_pitch_p95_deg", std::to_string(s.pitch95));
  ::testing::Test::RecordProperty(name + "_roll_p95_deg", std::to_string(s.roll95));
  ::testing::Test::RecordProperty(name + "_height_p95_m", std::to_string(s.height95));
  return s;
}

TEST(snvSyntheticPose, PitchOscillationMeetsTargets) {
  // 14 frames at 10 fps over the first 1.4 s: a full +-2 deg pitch swing with
  // heave and roll, before the climb 50 m ahead enters the 30 m ground range.
  const Summary s = summarise("pitch_oscillation", runScene("pitch_oscillation", 14, 1));
  EXPECT_LE(s.pitch95, 0.1);   // target (0.036 measured; 0.179 with the mean-shift pitch)
  EXPECT_LE(s.roll95, 0.1);    // target
  // The published (filtered) pose tracks the swing too: pitch 0.040 / roll 0.028 deg /
  // 1.2 cm measured with measurement variances 0.01 deg^2 / 0.01 deg^2 / 1e-4 m^2
  // (0.082 / 0.053 deg / 2.2 cm with the earlier 0.04 / 0.04 / 4e-4).
  EXPECT_LE(s.pub_pitch95, 0.1);
  EXPECT_LE(s.pub_roll95, 0.1);
  EXPECT_LE(s.pub_height95, 0.02);
  EXPECT_LE(s.height95, 0.02); // target
}

TEST(snvSyntheticPose, FlatRoadAndWetRoad) {
  const Summary urban = summarise("urban", runScene("urban", 6, 3));
  EXPECT_LE(urban.pitch95, 0.1);
  EXPECT_LE(urban.roll95, 0.1);  // target
  EXPECT_LE(urban.height95, 0.02);
  // wet_road: the same street with puddles mirroring the scene (trap pixels on
  // the road). The entropy of the plane residuals is higher with traps (target):
  // measured urban mean 2.81 bits, wet_road 3.29 bits.
  const Summary wet = summarise("wet_road", runScene("wet_road", 6, 3));
  EXPECT_LE(wet.height95, 0.06);
  EXPECT_LT(urban.entropy_mean + 0.25, wet.entropy_mean);
}

TEST(snvSyntheticPose, DefaultMatcherNervSgm) {
  // The same sequences with the pipeline's default matcher (nerv_sgm). With the
  // matcher's flat road-band census window (docs/stereo.md "Road accuracy") the
  // targets (pitch / roll 0.1 deg, height 2 cm at p95) are met: measured
  // pitch_oscillation 0.097 / 0.030 deg / 1.2 cm, urban 0.080 / 0.012 deg / 0.8 cm
  // (with the 9x7 window everywhere: 0.195 / 0.039 / 2.2 cm and 0.208 / 0.040 / 2.3 cm).
  // pitch_oscillation's pitch sits 0.003 deg under the target and its p95 is the
  // worst of 14 frames, so that one bound keeps 0.02 deg of room for other CPUs'
  // rounding; every other bound is the target.
  const Summary osc = summarise("nerv_sgm pitch_oscillation", runScene("pitch_oscillation", 14, 1, "nerv_sgm"));
  EXPECT_LE(osc.pitch95, 0.12);
  EXPECT_LE(osc.roll95, 0.1);
  EXPECT_LE(osc.height95, 0.02);
  const Summary urban = summarise("nerv_sgm urban", runScene("urban", 6, 3, "nerv_sgm"));
  EXPECT_LE(urban.pitch95, 0.1);
  EXPECT_LE(urban.roll95, 0.1);
  EXPECT_LE(urban.height95, 0.02);
}

TEST(snvSyntheticPose, ShortBaselineZedCamera) {
  // The urban scene seen by a ZED-like rig (config/cameras/zed.yaml: 1280 x 720, f 700 px,
  // baseline 0.12 m, 1.3 m over the road): fx * B is 84 px m against KITTI's 389, so the road's
  // disparity changes by 0.09 px a row and the per-normal pitch spreads over a 3.1-3.8 deg
  // mean-shift half-width. The mean shift then sat 0.4-1.0 deg off while the road plane on its
  // window was within 0.05 deg, and the fixed 0.5 deg gate kept the mean shift (p95 0.97 deg,
  // height 5.8 cm); the gate widens with the half-width (plane_pitch_gate_radius_share).
  const auto zed = [](synth::SceneSpec& spec) {
    StereoCamera& k = spec.camera.intrinsics;
    k.width = 1280;
    k.height = 720;
    k.fx = k.fy = 700.0;
    k.cx = 639.5;
    k.cy = 359.5;
    k.baseline_m = 0.12;
    spec.camera.height_m = 1.3;
  };
  const Summary s = summarise("nerv_sgm urban ZED", runScene("urban", 6, 3, "nerv_sgm", "zed", zed));
  EXPECT_LE(s.pitch95, 0.1);
  EXPECT_LE(s.roll95, 0.1);
  EXPECT_LE(s.height95, 0.02);
}

}  // namespace
}  // namespace nerv::snv

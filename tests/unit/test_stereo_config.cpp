// stereo_matcher configuration errors at start, and the bad-input checks the
// service applies to every frame (counted and dropped, never a crash).
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "message_check.hpp"
#include "stereo_matcher.hpp"

using namespace nerv;

namespace {

std::string configError(const std::string& yaml) {
  ConfigSection section(YAML::Load(yaml), "stereo_matcher");
  try {
    stereo::readParams(section);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

image_t gray(int w, int h) {
  image_t im;
  im.width = w;
  im.height = h;
  im.channels = 1;
  im.encoding = "gray8";
  im.data.assign(static_cast<size_t>(w) * h, 128);
  im.size = static_cast<int32_t>(im.data.size());
  return im;
}

stereo_frame_t frame(int w, int h) {
  stereo_frame_t f{};
  f.calib.width = w;
  f.calib.height = h;
  f.calib.fx = f.calib.fy = 700;
  f.calib.cx = w / 2.0;
  f.calib.cy = h / 2.0;
  f.calib.baseline_m = 0.5;
  f.calib.rectified = true;
  f.left = gray(w, h);
  f.right = gray(w, h);
  return f;
}

}  // namespace

TEST(stereoConfig, DefaultsAreValid) {
  EXPECT_EQ(configError("{}"), "");
  EXPECT_EQ(configError("{algorithm: sgbm_wls, num_disparities: 64, downscale: 2}"), "");
  EXPECT_NO_THROW(stereo::StereoMatcher::create(stereo::Params{}));
}

TEST(stereoConfig, BadValuesNameTheKey) {
  EXPECT_NE(configError("{num_disparities: 0}").find("stereo_matcher.num_disparities"), std::string::npos);
  EXPECT_NE(configError("{num_disparities: -32}").find("stereo_matcher.num_disparities"), std::string::npos);
  EXPECT_NE(configError("{num_disparities: 40}").find("stereo_matcher.num_disparities"), std::string::npos);
  EXPECT_NE(configError("{algorithm: magic}").find("stereo_matcher.algorithm"), std::string::npos);
  EXPECT_NE(configError("{sgm_p2: 230}").find("stereo_matcher.sgm_p2"), std::string::npos);
  EXPECT_NE(configError("{road_census_width: 12}").find("stereo_matcher.road_census_width"), std::string::npos);
  EXPECT_NE(configError("{road_census_width: 15, road_census_height: 5}").find("stereo_matcher.road_census_width"),
            std::string::npos);  // 37 pairs > 32 bits
  EXPECT_NE(configError("{road_census_from: 1.5}").find("stereo_matcher.road_census_from"), std::string::npos);
  EXPECT_EQ(configError("{road_census_from: 1}"), "");  // no road band
  EXPECT_NE(configError("{downscale: 3}").find("stereo_matcher.downscale"), std::string::npos);
  EXPECT_NE(configError("{census_width: 9, census_height: 9}").find("stereo_matcher.census_width"), std::string::npos);
  EXPECT_NE(configError("{census_width: 8}").find("stereo_matcher.census_width"), std::string::npos);
  stereo::Params p;
  p.algorithm = "magic";
  EXPECT_THROW(stereo::StereoMatcher::create(p), ConfigError);
  p = stereo::Params{};
  p.num_disparities = -16;
  EXPECT_THROW(stereo::StereoMatcher::create(p), ConfigError);
}

TEST(stereoConfig, BadFramesAreRejectedWithACounter) {
  Limits limits;
  limits.max_width = 640;
  limits.max_height = 480;
  EXPECT_FALSE(checkStereoFrame(frame(64, 48), limits));

  stereo_frame_t sizes = frame(64, 48);
  sizes.right = gray(60, 48);
  const Problem a = checkStereoFrame(sizes, limits);
  EXPECT_EQ(a.counter, "size_mismatch") << a.message;

  const Problem b = checkStereoFrame(frame(800, 48), limits);
  EXPECT_TRUE(b) << "image wider than max_width";
  EXPECT_FALSE(b.message.empty());

  stereo_frame_t calib = frame(64, 48);
  calib.calib.width = 128;
  const Problem c = checkStereoFrame(calib, limits);
  EXPECT_EQ(c.counter, "size_mismatch") << c.message;
}

TEST(stereoConfig, DescribeParamsNamesEveryFieldThatChangesTheDisparity) {
  const stereo::Params base;
  const std::string b = stereo::describeParams(base);
  EXPECT_EQ(b, stereo::describeParams(stereo::Params{}));
  stereo::Params t = base;
  t.threads = 1;
  EXPECT_EQ(stereo::describeParams(t), b) << "the thread count does not change the output";
  // each field changed alone gives another description
  std::vector<std::function<void(stereo::Params&)>> changes = {
      [](stereo::Params& p) { p.algorithm = "sgbm"; }, [](stereo::Params& p) { p.num_disparities = 64; },
      [](stereo::Params& p) { p.min_disparity = 2; }, [](stereo::Params& p) { p.downscale = 2; },
      [](stereo::Params& p) { p.uniqueness_ratio = 5; }, [](stereo::Params& p) { p.speckle_window_size = 50; },
      [](stereo::Params& p) { p.speckle_range = 1; }, [](stereo::Params& p) { p.lr_max_diff = 2; },
      [](stereo::Params& p) { p.block_size = 7; }, [](stereo::Params& p) { p.p1 = 100; },
      [](stereo::Params& p) { p.p2 = 900; }, [](stereo::Params& p) { p.bm_block_size = 21; },
      [](stereo::Params& p) { p.wls_lambda = 100; }, [](stereo::Params& p) { p.wls_sigma = 1.0; },
      [](stereo::Params& p) { p.census_width = 7; }, [](stereo::Params& p) { p.census_height = 5; },
      [](stereo::Params& p) { p.road_census_width = 11; }, [](stereo::Params& p) { p.road_census_height = 5; },
      [](stereo::Params& p) { p.road_census_from = 0.8; }, [](stereo::Params& p) { p.sgm_p1 = 5; },
      [](stereo::Params& p) { p.sgm_p2 = 60; }, [](stereo::Params& p) { p.subpixel = false; },
      [](stereo::Params& p) { p.boundary_snap_px = 0; }, [](stereo::Params& p) { p.gated_mean_radius = 0; },
      [](stereo::Params& p) { p.gated_mean_range_px = 1.0; },
      [](stereo::Params& p) { p.gated_mean_range_rel = 0.1; }};
  for (size_t i = 0; i < changes.size(); ++i) {
    stereo::Params p = base;
    changes[i](p);
    EXPECT_NE(stereo::describeParams(p), b) << "change " << i << " is not in the description";
  }
}

TEST(stereoConfig, EveryAcceptedRangeComputes) {
  // What readParams accepts must run: every algorithm, at full and half resolution, with
  // and without the near field, over ranges from 16 levels to the wire's 256 px, on a frame
  // of odd size. The matcher either refuses a combination at create() with a ConfigError
  // naming the key or computes a map of the frame's size (32 levels at half resolution was
  // refused by the inner matcher's own check until the sixth session of 2026-12-07).
  cv::Mat left(121, 333, CV_8UC1), right;
  cv::RNG rng(4);
  rng.fill(left, cv::RNG::UNIFORM, 0, 256);
  right = left.clone();
  int computed = 0, refused = 0;
  for (const char* algorithm : {"nerv_sgm", "sgbm", "sgbm_full", "sgbm_wls", "bm"})
    for (int downscale : {1, 2})
      for (int levels : {16, 32, 48, 64, 96, 128, 192, 256})
        for (int min_disparity : {0, 2, 7})
          for (bool near_field : {true, false}) {
            stereo::Params p;
            p.algorithm = algorithm;
            p.downscale = downscale;
            p.num_disparities = levels;
            p.min_disparity = min_disparity;
            p.near_field = near_field;
            const std::string what = std::string(algorithm) + " downscale " + std::to_string(downscale) + " levels " +
                                     std::to_string(levels) + " min " + std::to_string(min_disparity) +
                                     (near_field ? " near field" : "");
            std::unique_ptr<stereo::StereoMatcher> m;
            try {
              m = stereo::StereoMatcher::create(p);
            } catch (const ConfigError& e) {
              ++refused;
              EXPECT_NE(std::string(e.what()).find("stereo_matcher."), std::string::npos) << what << ": " << e.what();
              // the one cross-key rule of the half resolution, and nothing else
              EXPECT_TRUE(downscale == 2 && (levels % 32 != 0 || min_disparity % 2 != 0)) << what << ": " << e.what();
              continue;
            }
            cv::Mat disparity, confidence;
            EXPECT_NO_THROW(m->compute(left, right, disparity, confidence)) << what;
            EXPECT_EQ(disparity.size(), left.size()) << what;
            EXPECT_EQ(confidence.size(), left.size()) << what;
            ++computed;
          }
  EXPECT_GT(computed, 0);
  EXPECT_GT(refused, 0);
}

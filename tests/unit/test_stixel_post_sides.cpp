// Post sides across matcher holes (post_sides.hpp): a sign post narrower than
// its strip whose plate has holes beside the post and in its rows gets the
// plate's width; a post without a plate keeps its own; the config keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// The post's hypothesis (a box taller than 2 m at depth z), if any.
std::optional<Hypothesis> postAt(const std::vector<Hypothesis>& hs, float z) {
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < 1.0f && h.height_m > 2.0f) return h;
  return std::nullopt;
}

TEST(stixelPostSides, ASignPlateWithHolesWidensItsPostsBox) {
  // A 0.15 m post 3 m tall at 15 m with a 0.8 m wide, 0.6 m tall plate at its
  // top. The matcher leaves two invalid columns along each side of the post
  // (its left-right check) and every fourth plate row invalid (no texture).
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const float z = 15.0f;
  const FaceColumns post = paintFace(disp, scene, cam, z, -0.075, 0.075, 0.0, 3.0);
  const FaceColumns plate = paintFace(disp, scene, cam, z, -0.4, 0.4, 2.4, 3.0);
  const double foot = footRow(scene, cam, z), px_per_m = cam.fx / z;
  const int plate_top = static_cast<int>(std::lround(foot - 3.0 * px_per_m));
  const int plate_bottom = static_cast<int>(std::lround(foot - 2.4 * px_per_m));
  for (int v = plate_top; v < plate_bottom; v += 4) disp.row(v).colRange(plate.u0, plate.u1).setTo(0.0f);
  const int top = static_cast<int>(std::lround(foot - 3.0 * px_per_m)), bottom = static_cast<int>(std::lround(foot));
  disp(cv::Range(top, bottom), cv::Range(post.u0 - 2, post.u0)).setTo(0.0f);
  disp(cv::Range(top, bottom), cv::Range(post.u1, post.u1 + 2)).setTo(0.0f);
  ASSERT_NE(post.u0 % 5, 0) << "the post's left edge must lie inside a strip";

  Params off;
  off.post_sides_max_width_m = 0.0f;
  const std::optional<Hypothesis> narrow = postAt(estimateStixels(disp, cam, off).hypotheses, z);
  ASSERT_TRUE(narrow.has_value());
  EXPECT_GT(narrow->box.x, plate.u0 + 8) << "without the rule the box keeps the post's width";

  const std::optional<Hypothesis> wide = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z);
  ASSERT_TRUE(wide.has_value());
  EXPECT_NEAR(wide->box.x, plate.u0, 2);
  EXPECT_NEAR(wide->box.x + wide->box.w, plate.u1, 2);
}

TEST(stixelPostSides, APostWithoutAPlateKeepsItsWidthBesideABackgroundWall) {
  // The same post with its holes in front of a wall 5 m behind it: the wall's
  // pixels are valid at another depth, so no column beside the post joins.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const float z = 15.0f;
  paintFace(disp, scene, cam, 20.0f, -3.0, 3.0, 0.0, 3.5);
  const FaceColumns post = paintFace(disp, scene, cam, z, -0.075, 0.075, 0.0, 3.0);
  const double foot = footRow(scene, cam, z), px_per_m = cam.fx / z;
  const int top = static_cast<int>(std::lround(foot - 3.0 * px_per_m)), bottom = static_cast<int>(std::lround(foot));
  disp(cv::Range(top, bottom), cv::Range(post.u0 - 2, post.u0)).setTo(0.0f);
  disp(cv::Range(top, bottom), cv::Range(post.u1, post.u1 + 2)).setTo(0.0f);
  const std::optional<Hypothesis> h = postAt(estimateStixels(disp, cam, Params{}).hypotheses, z);
  ASSERT_TRUE(h.has_value());
  EXPECT_GE(h->box.x, post.u0 - 1);
  EXPECT_LE(h->box.x + h->box.w, post.u1 + 1);
}

TEST(stixelPostSides, KeysAreReadAndRangeChecked) {
  // Each key with a valid value it must be read as, then each below its range.
  const std::vector<std::pair<const char*, float Params::*>> keys = {
      {"post_sides_max_width_m", &Params::post_sides_max_width_m},
      {"post_sides_min_height_m", &Params::post_sides_min_height_m},
      {"post_sides_min_run_m", &Params::post_sides_min_run_m},
      {"post_sides_max_extension_m", &Params::post_sides_max_extension_m},
      {"post_sides_max_gap_m", &Params::post_sides_max_gap_m}};
  YAML::Node n;
  for (size_t i = 0; i < keys.size(); ++i) n[keys[i].first] = 0.25 + 0.1 * static_cast<double>(i);
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  for (size_t i = 0; i < keys.size(); ++i)
    EXPECT_FLOAT_EQ(p.*keys[i].second, 0.25f + 0.1f * static_cast<float>(i)) << keys[i].first;
  for (const auto& [key, field] : keys) {
    YAML::Node bad;
    bad[key] = -1.0;
    ConfigSection b(bad, "stixel");
    EXPECT_THROW(
        {
          try {
            readParams(b);
          } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
            throw;
          }
        },
        ConfigError)
        << key << " = -1 was accepted";
  }
}

}  // namespace
}  // namespace nerv::stixel

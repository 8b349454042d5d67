// Blended head rows (blended_tops.hpp): a far pedestrian's box that stops at
// the shoulders, with a head above it read as a blend of body and background,
// is raised to the head; without a blend (holes, sky) it stays; a car's box, a
// wide low one, a post's and a near pedestrian's are not raised; a nearer
// surface above ends the rise; the keys.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <vector>

#include "blended_tops.hpp"
#include "ground_geometry.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

constexpr float kFacadePx = 7.5f;  // the background behind every object (52 m)

struct Scene {
  StereoCamera cam = kittiLikeCamera();
  GroundModel ground;
  cv::Mat disp;
  std::vector<Stixel> stixels;

  Scene() {
    float a = 0, b = 0;
    groundLineFromPose(0.0f, 1.65f, cam, a, b);
    ground = groundModelFromLine(a, b, cam, "test");
    disp = cv::Mat(cam.height, cam.width, CV_32F, cv::Scalar(0.0f));
    for (int v = 0; v < disp.rows; ++v) disp.row(v).setTo(std::max(ground.groundDisparity(static_cast<float>(v)), kFacadePx));
  }
  float disparityAt(float z) const { return static_cast<float>(cam.disparityFromDepth(z)); }
  int footRow(float d) const { return static_cast<int>(std::lround((d - ground.vd_intercept) / ground.vd_slope)); }
  int rowAt(float z, float height_m) const { return footRow(disparityAt(z)) - static_cast<int>(height_m * cam.fy / z); }
  // An upright body at depth z over columns [u0, u1), visible up to height_m;
  // its strips become the group's stixels.
  PixelBox body(int u0, int u1, float z, float height_m) {
    const float d = disparityAt(z);
    const int foot = footRow(d), top = rowAt(z, height_m);
    disp(cv::Rect(u0, top, u1 - u0, foot - top + 1)).setTo(d);
    for (int u = u0; u < u1; u += 5) {
      Stixel s;
      s.u = u, s.width = std::min(5, u1 - u), s.disparity = d, s.depth_m = z;
      s.top_row = top, s.bottom_row = foot;
      stixels.push_back(s);
    }
    return {u0, u1, top, foot};
  }
  int raise(PixelBox& box, const BlendedTopParams& p = defaults()) const {
    std::vector<const Stixel*> g;
    for (const Stixel& s : stixels) g.push_back(&s);
    return raiseBlendedTop(disp, cam, ground, g, p, box);
  }
  static BlendedTopParams defaults() { return blendedTopParams(Params{}); }
};

// urban seed 11 frame 10: a pedestrian at 34 m (10.9 px, 16 px box) whose
// stixel top stops at the shoulders, 1.2 m over the road; its head (5 px wide,
// 0.4 m) reads 8.7-9.5 px between holes, the facade 7.5 px.
constexpr float kPedestrianZ = 34.0f;

// That pedestrian in s: returns its box (top at the shoulders); head_top is
// the row of its head's top, 1.6 m over the road.
PixelBox farPedestrian(Scene& s, int& head_top) {
  PixelBox box = s.body(440, 456, kPedestrianZ, 1.2f);
  head_top = s.rowAt(kPedestrianZ, 1.6f);
  s.disp(cv::Rect(446, head_top, 5, box.y0 - head_top)).setTo(9.2f);
  return box;
}

TEST(stixelBlendedTops, AFarPedestriansHeadReadAsABlendRaisesItsTop) {
  Scene s;
  int head_top = 0;
  PixelBox box = farPedestrian(s, head_top);
  s.disp(cv::Rect(447, head_top + 2, 2, 2)).setTo(0.0f);  // holes in the head
  const int before = box.y0;
  EXPECT_EQ(s.raise(box), before - head_top);
  EXPECT_EQ(box.y0, head_top);

  BlendedTopParams off = Scene::defaults();
  off.max_extension_m = 0.0f;
  PixelBox kept{440, 456, before, box.y1};
  EXPECT_EQ(s.raise(kept, off), 0) << "0 = off";
  EXPECT_EQ(kept.y0, before);
}

TEST(stixelBlendedTops, NoBlendAboveTheShouldersLeavesTheTop) {
  Scene s;
  PixelBox box = s.body(440, 456, kPedestrianZ, 1.2f);
  const int head_top = s.rowAt(kPedestrianZ, 1.6f);
  s.disp(cv::Rect(440, head_top, 16, box.y0 - head_top)).setTo(0.0f);  // unmatched rows (sky, holes)
  const int before = box.y0;
  EXPECT_EQ(s.raise(box), 0);
  EXPECT_EQ(box.y0, before);
  // The matcher's bias of the background beside the body (0.4 px) is no blend.
  Scene t;
  PixelBox b2 = t.body(440, 456, kPedestrianZ, 1.2f);
  t.disp(cv::Rect(436, head_top, 24, b2.y0 - head_top)).setTo(kFacadePx + 0.4f);
  EXPECT_EQ(t.raise(b2), 0);
}

// A parked car's rear piece (1.2 m wide) at 35 m, roof 1.45 m over the road:
// the window's blend over its roof does not raise it (higher than shoulders).
TEST(stixelBlendedTops, ACarsTopIsNotRaised) {
  Scene s;
  const float z = 35.0f;
  PixelBox box = s.body(600, 625, z, 1.45f);
  s.disp(cv::Rect(600, box.y0 - 3, 25, 3)).setTo(9.0f);
  const int before = box.y0;
  EXPECT_EQ(s.raise(box), 0);
  EXPECT_EQ(box.y0, before);
  // A low car (roof 1.3 m) seen whole, 1.8 m wide: wider than a person.
  Scene t;
  PixelBox wide = t.body(600, 637, z, 1.3f);
  t.disp(cv::Rect(600, wide.y0 - 3, 37, 3)).setTo(9.0f);
  EXPECT_EQ(t.raise(wide), 0);
}

// A post at 25 m (0.16 m wide), 2.5 m tall, and a low one (1.1 m) at 15 m,
// nearer than a person the window is as wide as.
TEST(stixelBlendedTops, APostsTopIsNotRaised) {
  Scene s;
  PixelBox tall = s.body(700, 705, 25.0f, 2.5f);
  s.disp(cv::Rect(700, tall.y0 - 3, 5, 3)).setTo(10.0f);
  EXPECT_EQ(s.raise(tall), 0);
  Scene t;
  PixelBox low = t.body(700, 706, 15.0f, 1.1f);
  t.disp(cv::Rect(700, low.y0 - 4, 6, 4)).setTo(15.0f);
  EXPECT_EQ(t.raise(low), 0);
}

// A nearer surface over the box (a tree's branch, a sign at 20 m) ends the
// rise below it; the extension limit caps it.
TEST(stixelBlendedTops, ANearerSurfaceOrTheLimitEndsTheRise) {
  Scene s;
  int head_top = 0;
  PixelBox box = farPedestrian(s, head_top);
  s.disp(cv::Rect(440, head_top + 3, 16, 2)).setTo(s.disparityAt(20.0f));
  const int before = box.y0;
  EXPECT_EQ(s.raise(box), before - (head_top + 5));
  EXPECT_EQ(box.y0, head_top + 5);

  Scene t;
  PixelBox b2 = t.body(440, 456, kPedestrianZ, 1.2f);
  const int high = t.rowAt(kPedestrianZ, 2.2f);
  t.disp(cv::Rect(446, high, 5, b2.y0 - high)).setTo(9.2f);
  BlendedTopParams p = Scene::defaults();
  p.max_extension_m = 0.3f;
  const int limit = static_cast<int>(std::floor(0.3f * t.cam.fy / kPedestrianZ));
  EXPECT_EQ(t.raise(b2, p), limit);
}

TEST(stixelBlendedTops, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"blended_top_max_extension_m", &Params::blended_top_max_extension_m},
                       {"blended_top_max_width_m", &Params::blended_top_max_width_m},
                       {"blended_top_min_top_m", &Params::blended_top_min_top_m},
                       {"blended_top_max_top_m", &Params::blended_top_max_top_m},
                       {"blended_top_min_distance_m", &Params::blended_top_min_distance_m},
                       {"blended_top_min_share", &Params::blended_top_min_share}},
                      {0.0, 1.2, 1.0, 1.4, 25.0, 0.5});
  expectRejected("blended_top_max_extension_m", 3.5);
  expectRejected("blended_top_max_width_m", 0.05);
  expectRejected("blended_top_min_share", 0.0);
  expectRejected("blended_top_min_share", 1.5);
  EXPECT_FLOAT_EQ(Params{}.blended_top_max_extension_m, 0.5f);
}

}  // namespace
}  // namespace nerv::stixel

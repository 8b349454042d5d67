// Free space, stixels and hypotheses on rendered scenes with known geometry, the
// fast path against the per-column reference, and the config reader.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "free_space.hpp"
#include "hypothesis_grouping.hpp"
#include "stixel_estimator.hpp"
#include "stixel_reference.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// Columns fully covered by a box face at level depth z (camera pitch small).
void boxColumns(const StereoCamera& cam, const SceneBox& b, int& u0, int& u1) {
  u0 = static_cast<int>(std::ceil(cam.cx + cam.fx * b.x_left_m / b.z_m));
  u1 = static_cast<int>(std::floor(cam.cx + cam.fx * b.x_right_m / b.z_m));
}

TEST(stixelFreeSpace, OneBoxAtKnownDistance) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.pitch_deg = 0.8f;
  const SceneBox box{18.0f, -1.0f, 1.0f, 1.5f};
  scene.boxes.push_back(box);
  const cv::Mat disp = renderDisparity(scene, cam);
  const StixelResult r = estimateStixels(disp, cam, Params{});
  ASSERT_TRUE(r.ground.valid);

  int u0, u1;
  boxColumns(cam, box, u0, u1);
  const double foot = footRow(scene, cam, box.z_m);
  int inside = 0;
  for (const Stixel& s : r.stixels) {
    const bool in_box = s.u >= u0 && s.u + s.width <= u1 + 1;
    EXPECT_TRUE(s.u + s.width > u0 - 5 && s.u < u1 + 5)
        << "stixel at u=" << s.u << " outside the box columns " << u0 << "-" << u1;
    if (!in_box) continue;
    ++inside;
    // Camera depth of the box foot (pitched camera: z_c = h*sin + z*cos).
    const double th = scene.pitch_deg * M_PI / 180;
    const double z_foot = scene.camera_height_m * std::sin(th) + box.z_m * std::cos(th);
    EXPECT_NEAR(s.depth_m, z_foot, 0.03 * z_foot);
    EXPECT_NEAR(s.bottom_row, foot, 2.0);
    EXPECT_NEAR(s.base_z_m, box.z_m, 0.5);
    EXPECT_NEAR(s.base_x_m, (s.u + 0.5 * s.width - cam.cx) * s.depth_m / cam.fx, 0.05);
    // Top: the box is 1.5 m tall; allow two rows.
    const double top_row = foot - 1.5 * cam.fy / box.z_m;
    EXPECT_NEAR(s.top_row, top_row, 3.0);
  }
  EXPECT_GE(inside, (u1 - u0) / cam.width * 0 + (u1 - u0) / 5 - 1);
  ASSERT_EQ(r.hypotheses.size(), 1u);
  const Hypothesis& h = r.hypotheses[0];
  EXPECT_EQ(h.id, 0);
  EXPECT_NEAR(h.z_m, box.z_m, 0.5);
  EXPECT_NEAR(h.x_m, 0.0, 0.15);
  EXPECT_NEAR(h.width_m, 2.0, 0.3);
  EXPECT_NEAR(h.height_m, 1.5, 0.2);
  EXPECT_NEAR(h.distance_m, std::sqrt(h.x_m * h.x_m + h.y_m * h.y_m + h.z_m * h.z_m), 1e-3);
  EXPECT_NEAR(h.box.y + h.box.h - 1, foot, 2.0);
  // A face square to the camera: its nearest part is at its depth.
  EXPECT_NEAR(h.nearest_z_m, h.z_m, 0.02 * h.z_m);
  EXPECT_LE(h.nearest_z_m, h.z_m + 1e-4f);
  // Its uncertainty: a disparity error of depth_sigma_px (0.35) at f B = fx * B,
  // z^2 * 0.35 / (f B): 0.29 m at 18 m on this camera.
  const double fb = cam.fx * cam.baseline_m;
  EXPECT_NEAR(h.nearest_z_sigma_m, h.nearest_z_m * h.nearest_z_m * 0.35 / fb, 1e-4 * h.nearest_z_m);
  Params wider;
  wider.depth_sigma_px = 0.7f;
  EXPECT_NEAR(estimateStixels(disp, cam, wider).hypotheses.at(0).nearest_z_sigma_m, 2 * h.nearest_z_sigma_m, 1e-4);
}

TEST(stixelFreeSpace, NearestPartOfAVehicleWithItsSideInView) {
  // A van's rear at 10 m (x 6.0..7.8 m, 130 px) and its left side receding from
  // 10 to 16 m along x = 6 m (painted as 0.25 m deep slices, 162 px): z_m sits
  // on the median stixel, on the side; nearest_z_m on the rear.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  for (float z = 15.75f; z >= 10.0f; z -= 0.25f) {
    // the slice of the side between depths z and z + 0.25 covers columns u(z + 0.25)..u(z)
    const double u_near = cam.cx + cam.fx * 6.0 / z, u_far = cam.cx + cam.fx * 6.0 / (z + 0.25);
    paintFace(disp, scene, cam, z, (u_far - cam.cx) * z / cam.fx, (u_near - cam.cx) * z / cam.fx, 0.0, 2.0);
  }
  paintFace(disp, scene, cam, 10.0f, 6.0, 7.8, 0.0, 2.0);
  const StixelResult r = estimateStixels(disp, cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  const Hypothesis* car = nullptr;
  for (const Hypothesis& h : r.hypotheses)
    if (!car || h.box.w > car->box.w) car = &h;
  ASSERT_NE(car, nullptr);
  EXPECT_NEAR(car->nearest_z_m, 10.0f, 0.2f);
  EXPECT_GT(car->z_m, car->nearest_z_m + 0.2f) << "the median stixel lies on the side";
  EXPECT_GE(car->num_stixels, 6);
}

TEST(stixelFreeSpace, ObstaclesBeyondMaxDistanceAndBelowMinHeightAreIgnored) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.boxes = {{70.0f, -2.0f, 2.0f, 2.0f},     // beyond max_distance_m = 60
                 {10.0f, 3.0f, 5.0f, 0.12f}};    // lower than ground_tolerance_m
  const StixelResult r = estimateStixels(renderDisparity(scene, cam), cam, Params{});
  ASSERT_TRUE(r.ground.valid);
  EXPECT_TRUE(r.stixels.empty());
  EXPECT_TRUE(r.hypotheses.empty());
}

TEST(stixelFreeSpace, NearerObstacleWinsInItsColumns) {
  // A small box in front of a wide wall: its columns end at the box.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  const SceneBox front{9.0f, -0.5f, 0.5f, 1.0f};
  scene.boxes = {front, {25.0f, -8.0f, 8.0f, 2.0f}};
  const StixelResult r = estimateStixels(renderDisparity(scene, cam), cam, Params{});
  int u0, u1;
  boxColumns(cam, front, u0, u1);
  int checked = 0, behind = 0;
  for (const Stixel& s : r.stixels) {
    if (s.u >= u0 && s.u + s.width <= u1) {
      if (s.depth_m > 20.0f) {  // the wall seen above the box: a second-layer stixel
        EXPECT_NEAR(s.depth_m, 25.0, 0.8);
        for (const Stixel& n : r.stixels)
          if (n.u == s.u && n.depth_m < 20.0f) {
            EXPECT_LT(s.bottom_row, n.top_row);
          }
        ++behind;
        continue;
      }
      EXPECT_NEAR(s.depth_m, 9.0, 0.3);
      ++checked;
    } else if (s.u + s.width < u0 - 5 || s.u > u1 + 5) {
      EXPECT_NEAR(s.depth_m, 25.0, 0.8);
    } else {
      continue;  // strips at the front box's edges see both depths
    }
  }
  EXPECT_GE(checked, 8);
  EXPECT_GE(behind, 8);  // the wall continues above the box
}

TEST(stixelFreeSpace, ATreeCrownOverThePavementDoesNotHideAPedestrianBelowIt) {
  // A crown 2.0-2.5 m over the road at 10 m, 2 m wide, and a 1.7 m pedestrian
  // at 15 m below it: the crown is nearer, but it does not come down to the
  // road, so the pedestrian (not the crown) bounds the free space there.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  auto paint = [&](float z, double x_left_m, double x_right_m, double bottom_m, double top_m) {
    const double foot = footRow(scene, cam, z), px_per_m = cam.fx / z;
    const int u0 = static_cast<int>(std::lround(cam.cx + x_left_m * px_per_m));
    const int u1 = static_cast<int>(std::lround(cam.cx + x_right_m * px_per_m));
    disp(cv::Range(static_cast<int>(std::lround(foot - top_m * px_per_m)),
                   static_cast<int>(std::lround(foot - bottom_m * px_per_m))),
         cv::Range(u0, u1))
        .setTo(static_cast<float>(cam.fx * cam.baseline_m / z));
  };
  paint(15.0f, -0.3, 0.3, 0.0, 1.7);
  paint(10.0f, -1.0, 1.0, 2.0, 2.5);
  auto pedestrians = [&](const Params& p) {
    int n = 0;
    for (const Hypothesis& h : estimateStixels(disp, cam, p).hypotheses)
      n += std::abs(h.z_m - 15.0f) < 1.0f && h.height_m > 1.4f ? 1 : 0;
    return n;
  };
  EXPECT_EQ(pedestrians(Params{}), 1);
  Params off;
  off.max_clearance_m = 0.0f;
  EXPECT_EQ(pedestrians(off), 0) << "without the clearance the crown takes the pedestrian's strips";
}

TEST(stixelGrouping, SplitsTwoBoxesAtDifferentDepthsAndMergesOneWideBox) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  // Adjacent in the image: the near box's right edge and the far box's left edge
  // meet at the same column.
  scene.boxes = {{12.0f, -3.0f, -0.5f, 1.5f}, {20.0f, -0.5f * 20 / 12, 2.5f, 1.5f},
                 {30.0f, 6.0f, 12.0f, 2.5f}};  // one wide box (a bus side on)
  const StixelResult r = estimateStixels(renderDisparity(scene, cam), cam, Params{});
  ASSERT_EQ(r.hypotheses.size(), 3u);
  EXPECT_NEAR(r.hypotheses[0].z_m, 12.0, 0.4);
  EXPECT_NEAR(r.hypotheses[1].z_m, 20.0, 0.7);
  EXPECT_NEAR(r.hypotheses[2].z_m, 30.0, 1.2);
  EXPECT_NEAR(r.hypotheses[2].width_m, 6.0, 0.4);
  EXPECT_GE(r.hypotheses[2].num_stixels, 20);
  for (size_t i = 0; i < r.hypotheses.size(); ++i) {
    EXPECT_EQ(r.hypotheses[i].id, static_cast<int>(i));  // 0..n-1 left to right
    if (i > 0) {
      EXPECT_GT(r.hypotheses[i].box.x, r.hypotheses[i - 1].box.x);
    }
  }
}

Stixel makeStixel(const StereoCamera& cam, int u, float depth) {
  Stixel s;
  s.u = u;
  s.width = 5;
  s.depth_m = depth;
  s.disparity = static_cast<float>(cam.disparityFromDepth(depth));
  s.bottom_row = 250;
  s.top_row = 150;
  return s;
}

TEST(stixelOccluded, PersonBehindACarGetsItsOwnHypothesis) {
  // A 1.1 m car at 7 m hides the lower body of a 1.8 m person at 12 m; the
  // person's upper body is seen above the car roof.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  const SceneBox car{7.0f, -1.0f, 1.0f, 1.1f}, person{12.0f, -0.1f, 0.5f, 1.8f};
  scene.boxes = {car, person};
  const cv::Mat disp = renderDisparity(scene, cam);
  int pu0, pu1;
  boxColumns(cam, person, pu0, pu1);
  const double person_top = footRow(scene, cam, person.z_m) - person.height_m * cam.fy / person.z_m;

  Params without;
  without.occluded_stixels = false;
  for (const Hypothesis& h : estimateStixels(disp, cam, without).hypotheses)
    EXPECT_GT(std::abs(h.z_m - person.z_m), 1.0f) << "without second-layer stixels the person has no box";

  const StixelResult r = estimateStixels(disp, cam, Params{});
  int behind = 0;
  for (const Stixel& s : r.stixels) {
    if (s.u < pu0 || s.u + s.width > pu1 || std::abs(s.depth_m - person.z_m) > 0.5f) continue;
    ++behind;
    EXPECT_NEAR(s.top_row, person_top, 3.0);
    EXPECT_NEAR(s.base_z_m, person.z_m, 0.5);  // the foot is hidden: the base comes from the road line
  }
  EXPECT_GE(behind, 3);
  int found = 0;
  for (const Hypothesis& h : r.hypotheses) {
    if (std::abs(h.z_m - person.z_m) > 0.5f) continue;
    ++found;
    EXPECT_NEAR(h.box.x, pu0, 6);
    EXPECT_NEAR(h.box.x + h.box.w, pu1, 6);
    EXPECT_NEAR(h.box.y, person_top, 3.0);
    EXPECT_NEAR(h.x_m, 0.2f, 0.3f);
    EXPECT_NEAR(h.y_m, cam.toPoint(cam.cx, footRow(scene, cam, person.z_m), cam.fx * cam.baseline_m / person.z_m).y, 0.1);
  }
  EXPECT_EQ(found, 1);
}

TEST(stixelOccluded, TheNearestSurfaceAboveTheOccluderWinsOverAFullerOneBehindIt) {
  // A 1 m occluder at 8 m; above it the upper 0.3 m of something at 12 m (the
  // next car of a parked row), and above that a facade at 30 m that fills more
  // pixels: the second layer is the thing at 12 m, as the free space would
  // choose the nearest obstacle.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const int u0 = static_cast<int>(cam.cx) / 5 * 5 - 20, u1 = u0 + 40;
  auto paint = [&](float z, double bottom_m, double top_m) {
    const double foot = footRow(scene, cam, z);
    disp(cv::Range(static_cast<int>(std::lround(foot - top_m * cam.fy / z)),
                   static_cast<int>(std::lround(foot - bottom_m * cam.fy / z))),
         cv::Range(u0, u1))
        .setTo(static_cast<float>(cam.fx * cam.baseline_m / z));
  };
  paint(30.0f, 0.2, 2.4);
  paint(12.0f, 0.0, 1.0);  // its lower part is hidden by the occluder
  paint(8.0f, 0.0, 1.0);
  auto secondLayerDepth = [&](const Params& p) {
    float z = 0;
    for (const Stixel& s : estimateStixels(disp, cam, p).stixels)
      if (s.u >= u0 && s.u + s.width <= u1 && s.depth_m > 9.0f) z = s.depth_m;
    return z;
  };
  EXPECT_NEAR(secondLayerDepth(Params{}), 12.0f, 0.5f);
  Params fullest;
  fullest.occluded_nearest = false;
  EXPECT_NEAR(secondLayerDepth(fullest), 30.0f, 2.0f) << "the fullest surface is the facade";
}

TEST(stixelGrouping, GapsAndMinimumSize) {
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  std::vector<Stixel> st;
  for (int u = 100; u < 130; u += 5) st.push_back(makeStixel(cam, u, 10.0f));  // 6 stixels
  st.push_back(makeStixel(cam, 130, 13.0f));                                   // depth jump, alone
  // Lateral gap 40 px at 10 m = 0.55 m < 0.6 m: joins across the stray stixel;
  // then 80 px = 1.1 m: splits.
  for (int u = 170; u < 185; u += 5) st.push_back(makeStixel(cam, u, 10.0f));
  for (int u = 265; u < 280; u += 5) st.push_back(makeStixel(cam, u, 10.0f));
  const auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 2u);  // the lone 13 m stixel is below min_stixels_per_hypothesis
  EXPECT_EQ(hs[0].num_stixels, 9);
  EXPECT_EQ(hs[0].box.x, 100);
  EXPECT_EQ(hs[0].box.w, 85);
  EXPECT_EQ(hs[1].num_stixels, 3);
  EXPECT_EQ(hs[1].id, 1);
}

TEST(stixelGrouping, APostInAHedgeLeavesTheHedgesGroup) {
  // A 0.6 m hedge at 15 m, 2 m wide, with a 1.3 m post (one strip) in it.
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  p.tower_min_height_m = 0.8f;
  std::vector<Stixel> st;
  auto stixel = [&](int u, float height_m) {
    Stixel s = makeStixel(cam, u, 15.0f);
    s.top_row = s.bottom_row - static_cast<int>(height_m * cam.fy / 15.0f);
    return s;
  };
  for (int u = 600; u < 700; u += 5) st.push_back(stixel(u, u == 650 ? 1.3f : 0.6f));
  const auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 3u);  // hedge left of the post, the post, hedge right of it
  EXPECT_EQ(hs[1].box.x, 650);
  EXPECT_EQ(hs[1].num_stixels, 1);
  EXPECT_NEAR(hs[1].height_m, 1.3f, 0.1f);
  // Off: one group.
  p.tower_min_height_m = 0.0f;
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u);
  // A wide tall part is the object itself (a van behind a car's bonnet), not a post.
  p.tower_min_height_m = 0.8f;
  for (auto& s : st)
    if (s.u >= 640) s.top_row = s.bottom_row - static_cast<int>(1.3f * cam.fy / 15.0f);
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u);
}

TEST(stixelGrouping, APostSeenAboveTheLawnInFrontOfItIsOneTower) {
  // A 0.4 m lawn edge at 12 m across 20 strips; a 3 m post at 13.4 m, four
  // strips wide, stands behind it. Its outer strips see the post from its foot
  // (first layer); its middle two see the lawn first and the post above it
  // (occluded layer, listed after the lawn as the estimator does). The lawn
  // stixels in the post's strips must not cut the post into three towers.
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  p.tower_min_height_m = 0.8f;
  auto stixel = [&](int u, float z, int bottom_row, float height_m) {
    Stixel s = makeStixel(cam, u, z);
    s.bottom_row = bottom_row;
    s.top_row = bottom_row - static_cast<int>(height_m * cam.fy / z);
    return s;
  };
  std::vector<Stixel> st;
  for (int u = 600; u < 700; u += 5) {
    const bool post = u >= 640 && u < 660, middle = u == 645 || u == 650;
    if (!post || middle) st.push_back(stixel(u, 12.0f, 250, 0.4f));
    if (post) {
      const int bottom = middle ? st.back().top_row - 1 : 246;
      st.push_back(stixel(u, 13.4f, bottom, 3.0f - (246 - bottom) * 13.4f / static_cast<float>(cam.fy)));
    }
  }
  auto postBoxes = [&](const std::vector<Hypothesis>& hs) {
    int n = 0;
    for (const Hypothesis& h : hs) n += h.height_m > 2.0f ? 1 : 0;
    return n;
  };
  const std::vector<Hypothesis> hs = groupStixels(st, cam, p);
  ASSERT_EQ(postBoxes(hs), 1);
  for (const Hypothesis& h : hs)
    if (h.height_m > 2.0f) {
      EXPECT_EQ(h.box.x, 640);
      EXPECT_EQ(h.box.w, 20);
      EXPECT_EQ(h.num_stixels, 4);
    }
  p.tower_companions = false;
  EXPECT_GT(postBoxes(groupStixels(st, cam, p)), 1) << "without the rule the lawn cuts the post";
}

TEST(stixelGrouping, APedestrianBesideATreeLeavesTheTreesGroup) {
  // A tree (trunk and crown, 8 m tall, 3 strips) and a 1.7 m pedestrian
  // (2 strips) right beside it, both at 15 m: one group by depth.
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  p.structure_min_height_m = 4.5f;
  std::vector<Stixel> st;
  for (int u = 600; u < 625; u += 5) {
    Stixel s = makeStixel(cam, u, 15.0f);
    const float height_m = u < 615 ? 8.0f : 1.7f;
    s.top_row = s.bottom_row - static_cast<int>(height_m * cam.fy / 15.0f);
    st.push_back(s);
  }
  auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_EQ(hs[1].box.x, 615);
  EXPECT_NEAR(hs[1].height_m, 1.7f, 0.1f);
  // Off, or a truck (4 m: lower than any tree) beside it: one group.
  p.structure_min_height_m = 0.0f;
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u);
  p.structure_min_height_m = 4.5f;
  for (Stixel& s : st)
    if (s.u < 615) s.top_row = s.bottom_row - static_cast<int>(4.0f * cam.fy / 15.0f);
  EXPECT_EQ(groupStixels(st, cam, p).size(), 1u);
}

// A stixel at column u and depth z whose top stands height_m over its foot.
Stixel stixelOfHeight(const StereoCamera& cam, int u, float z, float height_m) {
  Stixel s = makeStixel(cam, u, z);
  s.top_row = s.bottom_row - static_cast<int>(std::lround(height_m * cam.fy / z));
  return s;
}

// The left column of the 5 px strip that sees lateral offset x_m at depth z_m.
int stripAt(const StereoCamera& cam, double x_m, double z_m) {
  return static_cast<int>(cam.cx + cam.fx * x_m / z_m) / 5 * 5;
}

// A 0.8 m guard rail at lateral offset x_m (< 0), one strip per 5 px, seen
// from depth z_from_m to z_to_m.
std::vector<Stixel> railOf(const StereoCamera& cam, double x_m, double z_from_m, double z_to_m) {
  std::vector<Stixel> rail;
  for (int u = stripAt(cam, x_m, z_from_m); u < stripAt(cam, x_m, z_to_m); u += 5)
    rail.push_back(stixelOfHeight(cam, u, static_cast<float>(cam.fx * x_m / (u + 2.5 - cam.cx)), 0.8f));
  return rail;
}

// Appends the strip right of st's last one: depth z, top height_m over its foot.
void extend(const StereoCamera& cam, std::vector<Stixel>& st, float z, float height_m) {
  st.push_back(stixelOfHeight(cam, st.back().u + 5, z, height_m));
}

TEST(stixelGrouping, AGuardRailRunningUpToACarIsCutBeforeTheCar) {
  // A 0.8 m guard rail 5 m left of the camera, seen from 8 m to 17 m, ends at
  // a car's rear (1.5 m tall, X -4.7..-3.0 m) at 15.5 m: the rail's far end
  // and the car are within the grouping gap, so rail and car were one group.
  const StereoCamera cam = kittiLikeCamera();
  GroupingParams p;
  auto at = [&](int u, float z, float height_m) { return stixelOfHeight(cam, u, z, height_m); };
  auto column = [&](double x_m, double z_m) { return stripAt(cam, x_m, z_m); };
  std::vector<Stixel> rail = railOf(cam, -5.0, 8.0, 17.0), car;
  for (int u = rail.back().u + 5; u < column(-3.0, 15.5); u += 5) car.push_back(at(u, 15.5f, 1.5f));
  std::vector<Stixel> st = rail;
  st.insert(st.end(), car.begin(), car.end());
  p.split_chains = false;
  ASSERT_EQ(groupStixels(st, cam, p).size(), 1u) << "without the rule rail and car are one box";
  p.split_chains = true;
  auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_EQ(hs[1].box.x, car.front().u);
  EXPECT_EQ(hs[1].num_stixels, static_cast<int>(car.size()));

  // A face at the near end of the receding run is not cut (a car's rear and
  // its own side recede away from each other): a car's rear at 8 m just left
  // of where the rail starts.
  std::vector<Stixel> away;
  for (int u = column(-6.7, 8.0); u < rail.front().u; u += 5) away.push_back(at(u, 8.0f, 1.5f));
  away.insert(away.end(), rail.begin(), rail.end());
  EXPECT_EQ(groupStixels(away, cam, p).size(), 1u);
}

TEST(stixelGrouping, AFarRailWithDepthNoiseIsStillCutBeforeTheCar) {
  // Highway seed 23 frame 14: a rail 5 m left recedes from 12 m; its last four
  // strips before a car's rear at 18.3 m read 19.7, 19.8, 20.1, 19.5 m (the
  // matcher flattens the far rail): over four strips it does not recede, over
  // the eight before the car it does.
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Stixel> st = railOf(cam, -5.0, 12.0, 19.0);
  for (const float z : {19.7f, 19.8f, 20.1f, 19.5f}) extend(cam, st, z, 0.8f);
  const int car_u = st.back().u + 5;
  for (int k = 0; k < 8; ++k) extend(cam, st, 18.3f, 1.5f);
  GroupingParams p;
  p.chain_long_run_stixels = 0;
  p.chain_reversal_min_jump_px = 0;  // the depth reversal would cut here as well
  p.chain_face_min_height_ratio = 0;
  ASSERT_EQ(groupStixels(st, cam, p).size(), 1u) << "four strips alone do not see the far rail recede";
  p.chain_long_run_stixels = 8;
  const auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_EQ(hs[1].box.x, car_u);
  EXPECT_EQ(hs[1].num_stixels, 8);
}

TEST(stixelGrouping, ARailThatComesBackToANearerFaceIsCutThere) {
  // Highway seed 23 frame 6: a rail 5 m left recedes to 18.8 m, one strip
  // mixes rail and car (17.1 m), then a car's rear at 16.4-16.8 m. Four noisy
  // strips of the rear do not read "across", and the strip before them is the
  // car's, so the direction test leaves rail and car one 7.5 m box; the face
  // is 2.9 px nearer than the rail's far end.
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Stixel> st = railOf(cam, -5.0, 12.0, 18.8);
  extend(cam, st, 17.1f, 1.1f);
  const int car_u = st.back().u + 5;
  for (const float z : {16.44f, 16.52f, 16.73f, 16.82f, 16.63f, 16.48f, 16.46f, 16.66f, 16.85f, 16.67f})
    extend(cam, st, z, 1.5f);
  GroupingParams p;
  p.chain_face_min_height_ratio = 0;  // the depth reversal alone
  p.chain_reversal_min_jump_px = 0;
  ASSERT_EQ(groupStixels(st, cam, p).size(), 1u) << "the direction test alone keeps them one box";
  p.chain_reversal_min_jump_px = 1.0f;
  const auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 2u);
  // The mixed strip may go either way; the rail's strips stay with the rail.
  EXPECT_GE(hs[1].box.x, car_u - 5);
  EXPECT_LE(hs[1].box.x, car_u);
  EXPECT_GE(hs[1].num_stixels, 10);
  EXPECT_LE(hs[1].num_stixels, 11);
}

TEST(stixelGrouping, ALowRailRunningUpToATallFaceAtItsDepthIsCut) {
  // Highway seed 23 frame 22: a median rail (0.8 m) recedes to 34.8 m, where
  // an oncoming van (2.1 m tall) stands at the same depth: no depth step, the
  // van's front reads 35.4, 35.3, 35.4 m and then a strip 1.2 m deeper. The
  // van is 2.6 times as tall as the rail's end.
  const StereoCamera cam = kittiLikeCamera();
  std::vector<Stixel> st = railOf(cam, -12.0, 26.0, 34.8);
  const float rail_end = st.back().depth_m;
  const int van_u = st.back().u + 5;
  for (const float dz : {0.6f, 0.5f, 0.6f, 1.8f, 0.8f, 0.0f, -0.5f, -0.6f}) extend(cam, st, rail_end + dz, 2.1f);
  GroupingParams p;
  p.chain_face_min_height_ratio = 0;
  ASSERT_EQ(groupStixels(st, cam, p).size(), 1u) << "no depth step, no cut";
  p.chain_face_min_height_ratio = 1.5f;
  const auto hs = groupStixels(st, cam, p);
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_GE(hs[1].box.x, van_u - 5);  // the strip where they meet may go either way
  EXPECT_LE(hs[1].box.x, van_u);

  // A vehicle's own side is as tall as its rear: a truck's side (3.5 m)
  // receding to the right of its rear from 20 m stays one with it.
  std::vector<Stixel> truck;
  for (int u = stripAt(cam, -3.0, 20.0); u < stripAt(cam, -0.6, 20.0); u += 5)
    truck.push_back(stixelOfHeight(cam, u, 20.0f, 3.5f));
  for (float z = 20.8f; z < 28.0f; z += 0.8f) extend(cam, truck, z, 3.5f);
  p.side_max_stixels = 0;  // the side rule would join a side split off by depth anyway
  EXPECT_EQ(groupStixels(truck, cam, p).size(), 1u);
}

TEST(stixelGrouping, AVehiclesRecedingSideJoinsItsBody) {
  // A car's rear (1.5 m tall) at 30 m right of the principal point (6 strips);
  // its left side, seen at a grazing angle, recedes 2 m per strip towards the
  // image centre: each side strip is farther than the 1.5 m grouping gap.
  const StereoCamera cam = kittiLikeCamera();
  ASSERT_LT(cam.cx, 780.0);
  GroupingParams p;
  p.side_max_stixels = 3;
  auto car = [&](int u, float z, float height_m = 1.5f) {
    Stixel s = makeStixel(cam, u, z);
    s.top_row = s.bottom_row - static_cast<int>(std::lround(height_m * cam.fy / z));
    return s;
  };
  std::vector<Stixel> body;
  for (int u = 800; u < 830; u += 5) body.push_back(car(u, 30.0f));
  auto with = [&](std::vector<Stixel> extra) {
    extra.insert(extra.end(), body.begin(), body.end());
    std::sort(extra.begin(), extra.end(), [](const Stixel& a, const Stixel& b) { return a.u < b.u; });
    return groupStixels(extra, cam, p);
  };
  const std::vector<Stixel> side = {car(790, 34.0f), car(795, 32.0f)};
  auto hs = with(side);
  ASSERT_EQ(hs.size(), 1u);
  EXPECT_EQ(hs[0].box.x, 790);
  EXPECT_EQ(hs[0].box.w, 40);
  EXPECT_EQ(hs[0].num_stixels, 8);

  // Off: the side strips are lone stixels and dropped; the box is the rear only.
  p.side_max_stixels = 0;
  hs = with(side);
  ASSERT_EQ(hs.size(), 1u);
  EXPECT_EQ(hs[0].box.x, 800);
  p.side_max_stixels = 3;

  // The same strips on the outward side cannot be the car's side (a side
  // projects towards the vanishing point): not joined.
  hs = with({car(830, 32.0f), car(835, 34.0f)});
  ASSERT_EQ(hs.size(), 1u);
  EXPECT_EQ(hs[0].box.x + hs[0].box.w, 830);

  // The next car of a parked row, 6.5 m behind the rear (more than a car's
  // length): a box of its own.
  hs = with({car(790, 36.5f), car(795, 36.0f)});
  ASSERT_EQ(hs.size(), 2u);
  EXPECT_EQ(hs[1].box.x, 800);

  // Something nearer than the rear, or taller than the car (a pedestrian
  // beside it), is not its side.
  hs = with({car(790, 28.0f), car(795, 28.0f)});
  EXPECT_EQ(hs.size(), 2u);
  hs = with({car(790, 34.0f, 1.9f), car(795, 32.0f, 1.9f)});
  ASSERT_EQ(hs.size(), 1u);
  EXPECT_EQ(hs[0].box.x, 800);

  // A truck (3.6 m tall) is longer: its side may end 9 m behind its rear.
  for (Stixel& s : body) s = car(s.u, 30.0f, 3.6f);
  hs = with({car(790, 39.0f, 3.6f), car(795, 35.0f, 3.6f)});
  ASSERT_EQ(hs.size(), 1u);
  EXPECT_EQ(hs[0].box.x, 790);
}

TEST(stixelBoxes, SignPlateWidensItsPostsBox) {
  // A 0.15 m post 3 m tall at 15 m with a 0.8 m wide, 0.6 m tall plate at its top.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const float z = 15.0f, d = static_cast<float>(cam.fx * cam.baseline_m / z);
  const double foot = footRow(scene, cam, z), px_per_m = cam.fx / z;
  auto paint = [&](double x_left_m, double x_right_m, double bottom_m, double top_m) {
    const int u0 = static_cast<int>(std::lround(cam.cx + x_left_m * px_per_m));
    const int u1 = static_cast<int>(std::lround(cam.cx + x_right_m * px_per_m));
    const int v0 = static_cast<int>(std::lround(foot - top_m * px_per_m));
    const int v1 = static_cast<int>(std::lround(foot - bottom_m * px_per_m));
    disp(cv::Range(v0, v1), cv::Range(u0, u1)).setTo(d);
    return std::make_pair(u0, u1);
  };
  paint(-0.075, 0.075, 0.0, 3.0);
  const auto plate = paint(-0.4, 0.4, 2.4, 3.0);
  const StixelResult r = estimateStixels(disp, cam, Params{});
  int found = 0;
  for (const Hypothesis& h : r.hypotheses) {
    if (std::abs(h.z_m - z) > 0.5f) continue;
    ++found;
    EXPECT_NEAR(h.box.x, plate.first, 2);
    EXPECT_NEAR(h.box.x + h.box.w, plate.second, 2);
  }
  EXPECT_EQ(found, 1);
  Params off;
  off.refine_min_column_run_m = 0.0f;
  off.post_sides_max_width_m = 0.0f;  // the post-side scan (post_sides.hpp) would widen it too
  for (const Hypothesis& h : estimateStixels(disp, cam, off).hypotheses) {
    if (std::abs(h.z_m - z) < 0.5f) {
      EXPECT_GT(h.box.x, plate.first + 4) << "without runs the plate is not in the box";
    }
  }
}

TEST(stixelBoxes, APostInAHedgeIsCutAtItsOwnWidth) {
  // A 0.15 m post 1.4 m tall in a 0.6 m hedge, 3 m wide, both at 15 m. The
  // post leaves the hedge's group (splitTowers); below the hedge's top the
  // columns beside it are at its depth too, so only the rows above the hedge
  // show its edges.
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const float z = 15.0f, d = static_cast<float>(cam.fx * cam.baseline_m / z);
  const double foot = footRow(scene, cam, z), px_per_m = cam.fx / z;
  auto paint = [&](double x_left_m, double x_right_m, double top_m) {
    const int u0 = static_cast<int>(std::lround(cam.cx + x_left_m * px_per_m));
    const int u1 = static_cast<int>(std::lround(cam.cx + x_right_m * px_per_m));
    const int v0 = static_cast<int>(std::lround(foot - top_m * px_per_m));
    disp(cv::Range(v0, static_cast<int>(std::lround(foot))), cv::Range(u0, u1)).setTo(d);
    return std::make_pair(u0, u1);
  };
  paint(-1.5, 1.5, 0.6);
  const auto post = paint(0.02, 0.17, 1.4);
  auto postBox = [&](const Params& p) {
    Box best{};
    for (const Hypothesis& h : estimateStixels(disp, cam, p).hypotheses)
      if (std::abs(h.z_m - z) < 0.5f && h.height_m > 1.0f) best = h.box;
    return best;
  };
  const Box on = postBox(Params{});
  ASSERT_GT(on.w, 0) << "the post has a hypothesis of its own";
  EXPECT_NEAR(on.x, post.first, 1);
  EXPECT_NEAR(on.x + on.w, post.second, 1);
  Params off;
  off.tower_edges_above_surround = false;
  // Judged on all rows, the hedge beside the post widens its box, and then the
  // post fills too little of the box's top rows: the top drops to the hedge.
  const Box wide = postBox(off);
  EXPECT_TRUE(wide.w == 0 || wide.w > on.w + 3) << wide.x << " " << wide.w;
}

TEST(stixelReference, FastPathAgreesWithPerColumnReference) {
  const StereoCamera cam = kittiLikeCamera();
  RoadScene scene;
  scene.pitch_deg = -0.7f;
  scene.boxes = {{7.0f, -4.0f, -2.5f, 1.2f}, {14.0f, -1.0f, 1.0f, 1.6f},
                 {22.0f, 3.0f, 6.0f, 2.2f}, {40.0f, -12.0f, -6.0f, 1.5f}};
  const cv::Mat disp = renderDisparity(scene, cam);
  const Params p;
  const StixelResult fast = estimateStixels(disp, cam, p);
  ASSERT_TRUE(fast.ground.valid);
  const std::vector<Stixel> ref = referenceStixels(disp, cam, fast.ground, p);
  ASSERT_GT(ref.size(), 60u);
  size_t matched = 0;
  for (const Stixel& r : ref) {
    for (const Stixel& f : fast.stixels) {
      if (f.u != r.u) continue;
      EXPECT_NEAR(f.depth_m, r.depth_m, 0.03 * r.depth_m) << "u " << r.u;
      EXPECT_NEAR(f.bottom_row, r.bottom_row, 2) << "u " << r.u;
      EXPECT_NEAR(f.top_row, r.top_row, 3) << "u " << r.u;
      ++matched;
    }
  }
  // Strips at box edges may differ (partial coverage); the bulk must agree.
  EXPECT_GE(matched, ref.size() * 9 / 10);
  EXPECT_GE(fast.stixels.size(), ref.size() * 9 / 10);
}

// Every key with its default, so the test does not depend on how ConfigSection
// treats absent keys.
YAML::Node fullConfig() {
  const Params d;
  YAML::Node n;
  n["column_width_px"] = d.column_width_px;
  n["max_height_above_ground_m"] = d.max_height_above_ground_m;
  n["ground_tolerance_m"] = d.ground_tolerance_m;
  n["min_obstacle_height_m"] = d.min_obstacle_height_m;
  n["max_distance_m"] = d.max_distance_m;
  n["min_camera_height_m"] = d.min_camera_height_m;
  n["max_camera_height_m"] = d.max_camera_height_m;
  n["max_pitch_deg"] = d.max_pitch_deg;
  n["group_depth_gap_m"] = d.group_depth_gap_m;
  n["group_lateral_gap_m"] = d.group_lateral_gap_m;
  n["min_stixels_per_hypothesis"] = d.min_stixels_per_hypothesis;
  n["use_extrinsics_prior"] = d.use_extrinsics_prior;
  n["max_disparity_px"] = d.max_disparity_px;
  n["vd_inlier_tolerance_px"] = d.vd_inlier_tolerance_px;
  n["min_ground_rows"] = d.min_ground_rows;
  n["min_ground_disparity_span_px"] = d.min_ground_disparity_span_px;
  n["freespace_smoothness_m"] = d.freespace_smoothness_m;
  n["freespace_jump_cap_bins"] = d.freespace_jump_cap_bins;
  n["object_depth_tolerance_m"] = d.object_depth_tolerance_m;
  n["max_stixel_height_m"] = d.max_stixel_height_m;
  return n;
}

TEST(stixelParams, ReadsDeclaredKeysAndRejectsBadOnes) {
  YAML::Node n = fullConfig();
  n["column_width_px"] = 7;
  n["ground_tolerance_m"] = 0.2;
  n["use_extrinsics_prior"] = false;
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_EQ(p.column_width_px, 7);
  EXPECT_FLOAT_EQ(p.ground_tolerance_m, 0.2f);
  EXPECT_FALSE(p.use_extrinsics_prior);
  EXPECT_FLOAT_EQ(p.max_height_above_ground_m, Params{}.max_height_above_ground_m);

  YAML::Node bad = fullConfig();
  bad["column_width_px"] = 0;
  ConfigSection out_of_range(bad, "stixel");
  EXPECT_THROW(readParams(out_of_range), ConfigError);

  YAML::Node typo = fullConfig();
  typo["column_widht_px"] = 5;
  ConfigSection unknown(typo, "stixel");
  readParams(unknown);
  EXPECT_THROW(unknown.finish(), ConfigError);

  YAML::Node swapped = fullConfig();
  swapped["min_camera_height_m"] = 3.0;
  swapped["max_camera_height_m"] = 2.0;
  ConfigSection heights(swapped, "stixel");
  EXPECT_THROW(readParams(heights), ConfigError);
}

}  // namespace
}  // namespace nerv::stixel

// A surface just behind the top of a wide group (layered_tops.hpp): the strips
// of a car that ran up the rear of a truck 1.7 m behind it come down to the
// car's roof; a van's own taller middle, a narrow group and the rule switched
// off keep their tops; the keys.
#include <gtest/gtest.h>

#include <cmath>

#include "layered_tops.hpp"
#include "stixel_key_checks.hpp"
#include "stixel_test_stixels.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

class stixelLayeredTops : public ::testing::Test {
 protected:
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const GroundModel g = levelRoad(cam);

  int rowAt(double z, double height_m) const { return stixelOnRoad(cam, 0, z, height_m).top_row; }
  Stixel stixelAt(int u, double z, double top_m) const { return stixelOnRoad(cam, u, z, top_m); }
  static LayerTopParams on() {
    LayerTopParams p;
    p.min_separation_m = 1.0f;
    return p;
  }
};

// Highway seed 31, frames 7-9: a dark car at 21.5 m (1.45 m tall) in front of
// a truck's rear at 23.2 m (3.3 m tall); four of the car's twelve strips ran
// up the truck to its roof.
TEST_F(stixelLayeredTops, TopsThatRanUpATruckBehindComeDownToTheCar) {
  ASSERT_TRUE(g.valid);
  const FaceColumns truck = paintFace(disp, scene, cam, 23.2f, 0.0, 3.0, 0.0, 3.3);
  const FaceColumns car = paintFace(disp, scene, cam, 21.5f, 0.4, 2.4, 0.0, 1.45);
  ASSERT_LT(truck.u0, car.u0);
  std::vector<Stixel> own;
  for (int k = 0; k < 12; ++k) own.push_back(stixelAt(car.u0 + 5 * k, 21.5, k % 3 == 1 ? 3.3 : 1.45));
  ASSERT_LE(own.back().u + 5, car.u1);
  std::vector<Stixel*> group;
  for (Stixel& s : own) group.push_back(&s);
  EXPECT_EQ(lowerLayeredTops(disp, cam, g, group, on()), 4);
  for (const Stixel& s : own) EXPECT_NEAR(s.top_row, rowAt(21.5, 1.45), 2) << "strip at " << s.u;

  // Off: nothing moves.
  for (int k = 0; k < 12; ++k) own[static_cast<size_t>(k)] = stixelAt(car.u0 + 5 * k, 21.5, k % 3 == 1 ? 3.3 : 1.45);
  LayerTopParams off = on();
  off.min_separation_m = 0.0f;
  EXPECT_EQ(lowerLayeredTops(disp, cam, g, group, off), 0);
  EXPECT_EQ(own[1].top_row, rowAt(21.5, 3.3));
}

TEST_F(stixelLayeredTops, AVanTallerInTheMiddleKeepsItsTops) {
  // The taller middle is at the group's own depth: no layer behind it.
  const FaceColumns van = paintFace(disp, scene, cam, 21.5f, 0.4, 2.4, 0.0, 1.6);
  paintFace(disp, scene, cam, 21.5f, 1.0, 1.8, 1.6, 2.4);
  std::vector<Stixel> own;
  for (int k = 0; k < 12; ++k) {
    const int u = van.u0 + 5 * k;
    const double x = (u + 2.5 - cam.cx) * 21.5 / cam.fx;
    own.push_back(stixelAt(u, 21.5, x > 1.0 && x < 1.8 ? 2.4 : 1.6));
  }
  std::vector<Stixel*> group;
  for (Stixel& s : own) group.push_back(&s);
  const std::vector<Stixel> before = own;
  EXPECT_EQ(lowerLayeredTops(disp, cam, g, group, on()), 0);
  for (size_t i = 0; i < own.size(); ++i) EXPECT_EQ(own[i].top_row, before[i].top_row);
}

TEST_F(stixelLayeredTops, ANarrowGroupIsLeftAlone) {
  // A pedestrian's width in front of the same truck: the matcher reads far
  // torsos toward the background, which is no layer.
  paintFace(disp, scene, cam, 23.2f, 0.0, 3.0, 0.0, 3.3);
  const FaceColumns person = paintFace(disp, scene, cam, 21.5f, 1.0, 1.6, 0.0, 1.45);
  std::vector<Stixel> own;
  for (int k = 0; k < 3; ++k) own.push_back(stixelAt(person.u0 + 5 * k, 21.5, k == 1 ? 3.3 : 1.45));
  std::vector<Stixel*> group;
  for (Stixel& s : own) group.push_back(&s);
  EXPECT_EQ(lowerLayeredTops(disp, cam, g, group, on()), 0);
  EXPECT_EQ(own[1].top_row, rowAt(21.5, 3.3));
}

TEST_F(stixelLayeredTops, KeysAreReadAndRangeChecked) {
  expectFloatKeysRead({{"layer_top_min_separation_m", &Params::layer_top_min_separation_m},
                       {"layer_top_min_separation_px", &Params::layer_top_min_separation_px},
                       {"layer_top_min_share", &Params::layer_top_min_share},
                       {"layer_top_min_width_m", &Params::layer_top_min_width_m}},
                      {1.2, 0.6, 0.7, 1.5});
  expectRejected("layer_top_min_share", 1.5);
}

}  // namespace
}  // namespace nerv::stixel

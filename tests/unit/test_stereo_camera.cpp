#include <gtest/gtest.h>

#include "stereo_camera.hpp"

using namespace nerv;

namespace {
StereoCamera kitti() {
  StereoCamera c;
  c.width = 1242;
  c.height = 375;
  c.fx = c.fy = 721.5377;
  c.cx = 609.5593;
  c.cy = 172.854;
  c.baseline_m = 0.5327;
  return c;
}
}  // namespace

TEST(commonStereoCamera, DisparityTo3dFollowsTheTriangulationFormulas) {
  const StereoCamera c = kitti();
  const double u = 800, v = 250, d = 20;
  const Point3 p = c.toPoint(u, v, d);
  EXPECT_DOUBLE_EQ(p.z, c.fx * c.baseline_m / d);
  EXPECT_DOUBLE_EQ(p.x, (u - c.cx) * c.baseline_m / d);
  EXPECT_DOUBLE_EQ(p.y, (v - c.cy) * c.baseline_m / d);
}

TEST(commonStereoCamera, ProjectInvertsToPoint) {
  const StereoCamera c = kitti();
  for (double d : {1.0, 7.5, 64.0}) {
    const Point3 p = c.toPoint(123.25, 301.5, d);
    double u, v;
    ASSERT_TRUE(c.project(p, u, v));
    EXPECT_NEAR(u, 123.25, 1e-9);
    EXPECT_NEAR(v, 301.5, 1e-9);
    EXPECT_NEAR(c.disparityFromDepth(p.z), d, 1e-9);
  }
  double u, v;
  EXPECT_FALSE(c.project({0, 0, -1}, u, v));
}

TEST(commonStereoCamera, ProblemNamesBadValues) {
  EXPECT_EQ(kitti().problem(), "");
  StereoCamera c = kitti();
  c.baseline_m = 0;
  EXPECT_NE(c.problem().find("baseline"), std::string::npos);
  c = kitti();
  c.fx = std::nan("");
  EXPECT_NE(c.problem().find("focal"), std::string::npos);
  c = kitti();
  c.width = 0;
  EXPECT_NE(c.problem().find("size"), std::string::npos);
}

// The left edge of a box beside the matcher's occlusion band (box_refinement.hpp):
// a far narrow sign left of the image centre whose left-occluded band the
// matcher filled a fraction of a pixel below the sign's disparity gets its own
// edge; a car's side receding from the camera right of the centre stays in
// its box; an edge strip the band's tolerance empties keeps the usual edge;
// the tolerance itself against its formula; the config key.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>
#include <vector>

#include "box_refinement.hpp"
#include "stixel_estimator.hpp"
#include "stixel_key_checks.hpp"
#include "synthetic_road_scene.hpp"

namespace nerv::stixel {
namespace {

// The hypothesis whose depth is within 1.5 m of z, if any.
std::optional<Hypothesis> hypothesisAt(const std::vector<Hypothesis>& hs, float z) {
  for (const Hypothesis& h : hs)
    if (std::abs(h.z_m - z) < 1.5f) return h;
  return std::nullopt;
}

class stixelOccludedEdge : public ::testing::Test {
 protected:
  const StereoCamera cam = kittiLikeCamera();
  const RoadScene scene;
  cv::Mat disp = renderDisparity(scene, cam);
  const double fb = cam.fx * cam.baseline_m;
};

TEST_F(stixelOccludedEdge, AFarSignsOcclusionBandStaysOutsideItsBox) {
  // A sign 0.6 m wide and 2.2 m tall at 40 m, 5 m left of the camera, in front
  // of a wall at 80 m. The left camera sees d_sign - d_wall (4.9 px) of wall
  // left of the sign that the right camera does not; the matcher filled that
  // band with a ramp 0.6 to 0.9 px below the sign's disparity (as on KITTI
  // 0926, frames 3, 7, 8: band 9.3-10.0, sign 10.2-10.9): within the 1 px
  // floor, 4 m of depth at 40 m.
  const float z = 40.0f, z_wall = 80.0f;
  paintFace(disp, scene, cam, z_wall, -12.0, 4.0, 0.0, 5.0);
  const FaceColumns sign = paintFace(disp, scene, cam, z, -5.3, -4.7, 0.0, 2.2);
  ASSERT_LT(sign.u1, cam.cx) << "the sign must lie left of the principal point";
  const float d_sign = static_cast<float>(fb / z);
  const int band = static_cast<int>(std::lround(d_sign - fb / z_wall));
  ASSERT_GE(band, 4);
  const double foot = footRow(scene, cam, z), px_per_m = cam.fx / z;
  const int top = static_cast<int>(std::lround(foot - 2.2 * px_per_m)), bottom = static_cast<int>(std::lround(foot));
  for (int k = 1; k <= band; ++k)
    disp(cv::Range(top, bottom), cv::Range(sign.u0 - k, sign.u0 - k + 1))
        .setTo(d_sign - 0.6f - 0.3f * static_cast<float>(k - 1) / static_cast<float>(band - 1));

  Params off;
  off.refine_occluded_edge_tolerance_px = 0.0f;
  const std::optional<Hypothesis> wide = hypothesisAt(estimateStixels(disp, cam, off).hypotheses, z);
  ASSERT_TRUE(wide.has_value());
  EXPECT_LE(wide->box.x, sign.u0 - 3) << "without the rule the band is in the box";

  const std::optional<Hypothesis> h = hypothesisAt(estimateStixels(disp, cam, Params{}).hypotheses, z);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->box.x, sign.u0);
  EXPECT_EQ(h->box.x + h->box.w, wide->box.x + wide->box.w) << "the right edge is not changed";
}

TEST_F(stixelOccludedEdge, ACarsRecedingSideRightOfTheCentreStaysInItsBox) {
  // A car 1.8 m wide and 1.5 m tall at 35 m, its rear 3.2-5.0 m right of the
  // camera, and its left side (at 3.2 m, 35-39 m deep) seen left of the rear:
  // the side's disparity falls from the rear's 11.0 px to 10.0 px over 7
  // columns, as a real side does, d = B (u - cx) / X. The group holds only the
  // rear's stixels, so the side lies in the reach of the left edge's scan, up
  // to 1 px below the edge stixel's disparity (on wet_road seed 5, frames 2-5,
  // a flat 0.5 px floor cut such cars' boxes 5 px into their sides).
  const float z = 35.0f, z_back = 39.0f;
  const double x_side = 3.2;
  const FaceColumns rear = paintFace(disp, scene, cam, z, x_side, 5.0, 0.0, 1.5);
  const int side_u0 = static_cast<int>(std::lround(cam.cx + x_side * cam.fx / z_back));
  ASSERT_GE(rear.u0 - side_u0, 6);
  for (int u = side_u0; u < rear.u0; ++u) {
    const double zu = x_side * cam.fx / (u + 0.5 - cam.cx);
    const double x0 = (u - cam.cx) * zu / cam.fx, x1 = (u + 1 - cam.cx) * zu / cam.fx;
    paintFace(disp, scene, cam, static_cast<float>(zu), x0, x1, 0.0, 1.5);
  }
  const float d_rear = static_cast<float>(fb / z);
  ASSERT_GT(d_rear - disp.at<float>(static_cast<int>(footRow(scene, cam, z)) - 5, side_u0), 0.9f)
      << "the side's far end must lie below a flat 0.5 px floor";

  const StixelResult r = estimateStixels(disp, cam, Params{});
  std::vector<const Stixel*> group;
  for (const Stixel& st : r.stixels)
    if (std::abs(st.disparity - d_rear) < 0.05f && st.u + st.width > rear.u0 && st.u < rear.u1) group.push_back(&st);
  ASSERT_GE(group.size(), 6u);
  ASSERT_LE(group.front()->u, rear.u0);
  ASSERT_GT(group.front()->u + group.front()->width, rear.u0);
  PixelBox uni{group.front()->u, group.back()->u + group.back()->width, group.front()->top_row,
               group.front()->bottom_row};
  const Params d;
  BoxRefinementParams p = boxRefinementParams(d);
  ASSERT_GT(p.occluded_edge_tolerance_px, 0.0f);
  PixelBox after = uni;
  refineBox(disp, cam, r.ground, group, d.column_width_px, p, after);
  p.occluded_edge_tolerance_px = 0.0f;
  PixelBox before = uni;
  refineBox(disp, cam, r.ground, group, d.column_width_px, p, before);
  ASSERT_LE(before.x0, side_u0 + 1) << "the side is in the box without the rule";
  EXPECT_EQ(after.x0, before.x0);
  EXPECT_EQ(after.x1, before.x1);
}

TEST_F(stixelOccludedEdge, AnEdgeStripTheBandsToleranceEmptiesKeepsTheUsualEdge) {
  // A group whose left stixel's strip holds nothing within 0.5 px of its
  // disparity (KITTI 0926 frame 9: a low foot stixel whose rows are mostly
  // road) but 0.7 px below it in its last three columns: the usual 1 px test
  // puts the edge there; the band's test alone would find no column and keep
  // the union's edge, two columns wider.
  const float z = 38.0f, d = static_cast<float>(fb / z);
  const FaceColumns face = paintFace(disp, scene, cam, z, -4.0, -3.0, 0.0, 2.0);
  const int u0 = (face.u0 + 4) / 5 * 5;  // the first strip wholly inside the face
  std::vector<Stixel> st;
  const int top = static_cast<int>(std::lround(footRow(scene, cam, z) - 2.0 * cam.fy / z));
  const int bottom = static_cast<int>(std::lround(footRow(scene, cam, z)));
  for (int u = u0; u + 5 <= face.u1; u += 5) {
    Stixel s;
    s.u = u, s.width = 5, s.top_row = top, s.bottom_row = bottom, s.disparity = d, s.depth_m = z;
    st.push_back(s);
  }
  ASSERT_GE(st.size(), 2u);
  disp(cv::Range(0, cam.height), cv::Range(face.u0, u0 + 2)).setTo(0.0f);
  disp(cv::Range(top, bottom), cv::Range(u0 + 2, u0 + 5)).setTo(d - 0.7f);
  std::vector<const Stixel*> group;
  for (const Stixel& s : st) group.push_back(&s);
  const GroundModel ground = estimateStixels(renderDisparity(scene, cam), cam, Params{}).ground;
  BoxRefinementParams p;
  p.occluded_edge_tolerance_px = 0.5f;
  PixelBox box{u0, st.back().u + 5, top, bottom};
  refineBox(disp, cam, ground, group, 5, p, box);
  EXPECT_EQ(box.x0, u0 + 2);
}

TEST(stixelOccludedEdgeTolerance, IsTheFloorOrTheMetricToleranceLeftOfTheCentrePlusASidesDropRightOfIt) {
  const StereoCamera cam = kittiLikeCamera();
  const double fb = cam.fx * cam.baseline_m;
  Stixel s;
  s.width = 5;
  s.disparity = 10.0f;  // 38 m: the metric tolerance of 1 m is 0.26 px
  s.u = 500;            // left of cx (609.6): no receding side on the left
  EXPECT_FLOAT_EQ(occludedEdgeTolerance(s, 495, cam, 1.0f, 0.5f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(occludedEdgeTolerance(s, 495, cam, 1.0f, 0.0f, 1.0f), 1.0f) << "0 turns it off";
  s.disparity = 25.0f;  // 15 m: the metric tolerance (1.61 px) is above the floor, capped
  EXPECT_FLOAT_EQ(occludedEdgeTolerance(s, 495, cam, 1.0f, 0.5f, 1.0f), 1.0f);
  EXPECT_NEAR(occludedEdgeTolerance(s, 495, cam, 0.5f, 0.5f, 2.0f), 25.0 * 25.0 * 0.5 / fb, 1e-4);
  s.disparity = 10.0f;
  s.u = 700;  // right of cx: centre 702.5, a side drops 10 (702.5 - u) / (702.5 - cx) px
  const double drop = 10.0 * (702.5 - 698) / (702.5 - cam.cx);
  EXPECT_NEAR(occludedEdgeTolerance(s, 698, cam, 1.0f, 0.5f, 1.0f), 0.5 + drop, 1e-4);
  EXPECT_FLOAT_EQ(occludedEdgeTolerance(s, 690, cam, 1.0f, 0.5f, 1.0f), 1.0f) << "capped";
  EXPECT_FLOAT_EQ(occludedEdgeTolerance(s, 703, cam, 1.0f, 0.5f, 1.0f), 0.5f) << "no drop right of the centre";
}

TEST(stixelOccludedEdgeKey, IsReadAndRangeChecked) {
  YAML::Node n;
  n["refine_occluded_edge_tolerance_px"] = 0.3;
  ConfigSection c(n, "stixel");
  EXPECT_FLOAT_EQ(readParams(c).refine_occluded_edge_tolerance_px, 0.3f);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(Params{}.refine_occluded_edge_tolerance_px, 0.5f);
  expectRejected("refine_occluded_edge_tolerance_px", -0.1);
  expectRejected("refine_occluded_edge_tolerance_px", 1.5);
}

}  // namespace
}  // namespace nerv::stixel

// Second boxes on one object (duplicates.hpp): only boxes that agree on rows,
// depth and IoU are one object; road users at another object's depth stay.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include "duplicates.hpp"
#include "validator.hpp"

namespace nerv::validator {
namespace {

Hypothesis box(int id, int x, int y, int w, int h, float z) {
  Hypothesis hy;
  hy.id = id;
  hy.box = {x, y, w, h};
  hy.z_m = hy.distance_m = z;
  hy.height_m = 1.2f;
  hy.width_m = 0.3f;
  return hy;
}

std::vector<Verdict> keptObjects(size_t n) {
  std::vector<Verdict> v(n);
  for (size_t i = 0; i < n; ++i) v[i].roi_id = static_cast<int>(i), v[i].label = "object", v[i].kept = true;
  return v;
}

TEST(validatorDuplicates, BoxIouOfHandComputedCases) {
  EXPECT_FLOAT_EQ(boxIou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0f);
  EXPECT_FLOAT_EQ(boxIou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0f / 150.0f);
  EXPECT_FLOAT_EQ(boxIou({0, 0, 10, 10}, {10, 0, 10, 10}), 0.0f);  // columns [x, x + w): touching, no overlap
}

TEST(validatorDuplicates, TheWeakerOfTwoBoxesOnOnePostIsRemoved) {
  // KITTI 0926 frame 9: a post at 13.0 m boxed twice, 785-803 and 790-802 over
  // rows 210/212-273 (IoU 0.67); the box with fewer normals goes, with a reason.
  const std::vector<Hypothesis> h = {box(18, 785, 210, 18, 63, 13.0f), box(20, 790, 212, 12, 61, 13.0f)};
  std::vector<Verdict> v = keptObjects(2);
  EXPECT_EQ(removeDuplicates(h, {21, 18}, v, DuplicateParams{}), 1);
  EXPECT_TRUE(v[0].kept);
  EXPECT_FALSE(v[1].kept);
  EXPECT_NE(v[1].reason.find("duplicate of hypothesis 18"), std::string::npos) << v[1].reason;
  // Off: both stay.
  std::vector<Verdict> off = keptObjects(2);
  DuplicateParams none;
  none.min_iou = 0;
  EXPECT_EQ(removeDuplicates(h, {21, 18}, off, none), 0);
  EXPECT_TRUE(off[1].kept);
}

TEST(validatorDuplicates, RoadUsersAtAnotherObjectsDepthStay) {
  std::vector<Verdict> v = keptObjects(2);
  // A cyclist (658-675, 35.5 m) before a car 2 m behind (658-681, 37.5 m): IoU 0.70, depth 5.6 % apart.
  EXPECT_EQ(removeDuplicates({box(1, 658, 168, 17, 31, 35.5f), box(2, 658, 168, 23, 29, 37.5f)}, {23, 35}, v,
                             DuplicateParams{}),
            0);
  // A pedestrian (12.7 m) at a post (12.8 m) whose box reaches far higher: other rows.
  EXPECT_EQ(removeDuplicates({box(1, 1028, 154, 37, 105, 12.7f), box(2, 1025, 31, 38, 229, 12.8f)}, {74, 285}, v,
                             DuplicateParams{}),
            0);
  // Two boxes side by side at one depth: IoU below the threshold.
  EXPECT_EQ(removeDuplicates({box(1, 100, 100, 20, 40, 20.0f), box(2, 112, 100, 20, 40, 20.0f)}, {10, 10}, v,
                             DuplicateParams{}),
            0);
  // Removed or unknown depths are never compared.
  std::vector<Verdict> one = keptObjects(2);
  one[1].kept = false;
  EXPECT_EQ(removeDuplicates({box(1, 100, 100, 20, 40, 20.0f), box(2, 100, 100, 20, 40, 20.0f)}, {5, 9}, one,
                             DuplicateParams{}),
            0);
  EXPECT_TRUE(one[0].kept);
}

TEST(validatorDuplicates, ValidateRemovesTheDuplicateAndReadsItsKeys) {
  const std::vector<Hypothesis> h = {box(1, 785, 210, 18, 63, 13.0f), box(2, 790, 212, 12, 61, 13.0f)};
  std::vector<NormalStats> s(2);
  for (int i = 0; i < 2; ++i) {
    s[i].roi_id = i + 1;
    s[i].num_normals = i == 0 ? 21 : 18;
    s[i].num_samples = 40;
    s[i].density = s[i].num_normals / 40.0f;
    s[i].object_fraction = 0.5f;
    s[i].tilt_from_ground_deg = 90.0f;
  }
  const auto v = validate(h, s, Params{});
  ASSERT_EQ(v.size(), 2u);
  EXPECT_TRUE(v[0].kept);
  EXPECT_FALSE(v[1].kept);
  EXPECT_EQ(v[1].label, "object");  // the class stays; only the box goes

  YAML::Node n;
  n["duplicate_min_iou"] = 0.6;
  n["duplicate_max_row_offset_px"] = 5;
  n["duplicate_max_depth_ratio"] = 0.1;
  ConfigSection c(n, "validator");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(p.duplicates.min_iou, 0.6f);
  EXPECT_EQ(p.duplicates.max_row_offset_px, 5);
  EXPECT_FLOAT_EQ(p.duplicates.max_depth_ratio, 0.1f);
  YAML::Node bad;
  bad["duplicate_min_iou"] = 1.5;
  ConfigSection out_of_range(bad, "validator");
  EXPECT_THROW(readParams(out_of_range), ConfigError);
}

}  // namespace
}  // namespace nerv::validator

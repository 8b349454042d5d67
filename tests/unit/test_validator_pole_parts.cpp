// Parts of one pole boxed twice (pole_parts.hpp): of narrow, tall kept boxes
// over the same columns at one depth the tallest stays; road users, poles
// side by side and poles at another depth are not parts.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include "pole_parts.hpp"
#include "validator.hpp"

namespace nerv::validator {
namespace {

Hypothesis box(int id, int x, int y, int w, int h, float z, float height_m, float width_m) {
  Hypothesis hy;
  hy.id = id;
  hy.box = {x, y, w, h};
  hy.z_m = hy.distance_m = z;
  hy.height_m = height_m;
  hy.width_m = width_m;
  return hy;
}

std::vector<Verdict> keptObjects(size_t n) {
  std::vector<Verdict> v(n);
  for (size_t i = 0; i < n; ++i) v[i].roi_id = static_cast<int>(i), v[i].label = "object", v[i].kept = true;
  return v;
}

TEST(validatorPoleParts, TheShorterBoxesOfOnePoleGo) {
  // KITTI 0926 frame 4: one pole at 12.0-13.4 m boxed three times; the pole's
  // label matches the tallest (4.93 m), which has the fewest normals.
  const std::vector<Hypothesis> h = {box(28, 1000, 100, 60, 179, 12.5f, 3.10f, 1.04f),
                                     box(29, 1017, 13, 33, 267, 12.0f, 4.43f, 0.55f),
                                     box(30, 1024, 3, 35, 265, 13.4f, 4.93f, 0.65f)};
  std::vector<Verdict> v = keptObjects(3);
  EXPECT_EQ(removePoleParts(h, {249, 259, 241}, v, PolePartParams{}, 1.2f), 2);
  EXPECT_FALSE(v[0].kept);
  EXPECT_FALSE(v[1].kept);
  EXPECT_TRUE(v[2].kept);
  EXPECT_EQ(v[1].reason, "part of the pole of hypothesis 30 (79 % of its columns, 4.9 m tall)");
  EXPECT_EQ(v[0].label, "object");  // the class stays; only the box goes
}

TEST(validatorPoleParts, ABoxOfTheSecondPostHeightIsAPartToo) {
  // KITTI 0926 frame 5 (since saturated sky is left unmeasured): the post at 12 m as a
  // 4.59 m box and a 2.46 m one over the same columns.
  const std::vector<Hypothesis> h = {box(25, 1065, 132, 39, 143, 12.4f, 2.46f, 0.67f),
                                     box(28, 1076, 3, 37, 275, 12.0f, 4.59f, 0.62f)};
  std::vector<Verdict> v = keptObjects(2);
  EXPECT_EQ(removePoleParts(h, {70, 207}, v, PolePartParams{}, 1.2f), 1);
  EXPECT_FALSE(v[0].kept);
  EXPECT_TRUE(v[1].kept);
}

// Both boxes stay kept.
void expectNoPart(const Hypothesis& a, const Hypothesis& b, const char* what) {
  std::vector<Verdict> v = keptObjects(2);
  EXPECT_EQ(removePoleParts({a, b}, {100, 80}, v, PolePartParams{}, 1.2f), 0) << what;
  EXPECT_TRUE(v[0].kept && v[1].kept) << what;
}

TEST(validatorPoleParts, RoadUsersNeighboursAndOtherDepthsStay) {
  const Hypothesis pole = box(1, 500, 50, 20, 200, 15.0f, 5.0f, 0.4f);
  expectNoPart(pole, box(2, 498, 170, 24, 80, 15.2f, 1.8f, 0.5f), "a pedestrian at the pole's foot");
  expectNoPart(pole, box(2, 516, 60, 20, 190, 15.0f, 4.5f, 0.4f), "a pole beside it sharing 4 of 20 columns");
  expectNoPart(box(1, 500, 20, 30, 230, 20.0f, 7.0f, 1.0f), box(2, 505, 100, 15, 140, 16.0f, 3.0f, 0.3f),
               "a post 20 % in front of a tree trunk");
  expectNoPart(box(1, 480, 10, 80, 240, 15.0f, 8.0f, 3.0f), pole, "a 3 m wide box over the pole");
}

TEST(validatorPoleParts, OnlyKeptBoxesCountAndZeroTurnsItOff) {
  const std::vector<Hypothesis> h = {box(1, 500, 50, 20, 200, 15.0f, 5.0f, 0.4f),
                                     box(2, 502, 80, 16, 170, 15.5f, 4.0f, 0.35f)};
  // The taller one was removed already (say as an error): the shorter is no part of it.
  std::vector<Verdict> v = keptObjects(2);
  v[0].kept = false;
  EXPECT_EQ(removePoleParts(h, {100, 90}, v, PolePartParams{}, 1.2f), 0);
  EXPECT_TRUE(v[1].kept);
  PolePartParams off;
  off.min_height_m = 0.0f;
  v = keptObjects(2);
  EXPECT_EQ(removePoleParts(h, {100, 90}, v, off, 1.2f), 0);
  // Same height: the one with fewer normals is the part.
  const std::vector<Hypothesis> same = {box(1, 500, 50, 20, 200, 15.0f, 5.0f, 0.4f),
                                        box(2, 502, 50, 16, 200, 15.0f, 5.0f, 0.35f)};
  v = keptObjects(2);
  EXPECT_EQ(removePoleParts(same, {80, 90}, v, PolePartParams{}, 1.2f), 1);
  EXPECT_FALSE(v[0].kept);
  EXPECT_TRUE(v[1].kept);
}

TEST(validatorPoleParts, ValidateUsesThePoleWidthAndReadsItsKeys) {
  // Below the validator's 4.5 m height check, which exempts only boxes narrower than pole_max_width_m.
  const std::vector<Hypothesis> h = {box(1, 1024, 3, 35, 240, 13.4f, 4.40f, 0.65f),
                                     box(2, 1017, 13, 33, 220, 12.0f, 3.90f, 0.55f)};
  std::vector<NormalStats> s(2);
  for (int i = 0; i < 2; ++i) {
    s[i].roi_id = i + 1;
    s[i].num_normals = 240;
    s[i].num_samples = 500;
    s[i].density = 0.48f;
    s[i].object_fraction = 0.6f;
    s[i].tilt_from_ground_deg = 80.0f;
  }
  Params p;
  auto v = validate(h, s, p);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_TRUE(v[0].kept);
  EXPECT_FALSE(v[1].kept);
  p.pole_max_width_m = 0.5f;  // the validator's pole width decides what is pole-like
  v = validate(h, s, p);
  EXPECT_TRUE(v[0].kept && v[1].kept);

  YAML::Node n;
  n["pole_part_min_height_m"] = 3.0;
  n["pole_part_max_depth_ratio"] = 0.1;
  n["pole_part_min_overlap"] = 0.6;
  ConfigSection c(n, "validator");
  const Params q = readParams(c);
  EXPECT_NO_THROW(c.finish());
  EXPECT_FLOAT_EQ(q.pole_parts.min_height_m, 3.0f);
  EXPECT_FLOAT_EQ(q.pole_parts.max_depth_ratio, 0.1f);
  EXPECT_FLOAT_EQ(q.pole_parts.min_overlap, 0.6f);
  YAML::Node bad;
  bad["pole_part_min_overlap"] = 1.5;
  ConfigSection out_of_range(bad, "validator");
  EXPECT_THROW(readParams(out_of_range), ConfigError);
}

}  // namespace
}  // namespace nerv::validator

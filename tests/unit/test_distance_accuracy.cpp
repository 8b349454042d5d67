// Distance accuracy of detections: the labelled object's nearest depth and the
// per-band error summary, against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "distance_accuracy.hpp"

using namespace nerv;

namespace {
KittiLabel box3d(float x, float z, float l, float w, float ry) {
  KittiLabel k;
  k.type = "Car";
  k.x = x, k.y = 1.65f, k.z = z;
  k.h = 1.5f, k.w = w, k.l = l;
  k.rotation_y = ry;
  return k;
}
}  // namespace

TEST(toolsDistanceAccuracy, NearestDepthOfABoxSeenFromBehindIsItsRear) {
  // Heading along +z (KITTI rotation_y = -pi/2): the length runs along z, the rear is l/2 nearer.
  EXPECT_NEAR(labelNearestDepth(box3d(0, 20, 4, 1.8f, -static_cast<float>(M_PI) / 2)), 18.0f, 1e-4);
  // Oncoming (+pi/2): the same.
  EXPECT_NEAR(labelNearestDepth(box3d(3, 20, 4, 1.8f, static_cast<float>(M_PI) / 2)), 18.0f, 1e-4);
  // Crossing (rotation_y 0): the length runs along x, the width along z.
  EXPECT_NEAR(labelNearestDepth(box3d(0, 20, 4, 1.8f, 0)), 19.1f, 1e-4);
  // 45 degrees: the nearest corner is (l/2 + w/2) / sqrt(2) nearer.
  EXPECT_NEAR(labelNearestDepth(box3d(0, 20, 4, 2, static_cast<float>(M_PI) / 4)), 20 - 3 / std::sqrt(2.0f), 1e-4);
}

TEST(toolsDistanceAccuracy, LabelsWithoutSizeUseTheirDepthAndNoDepthIsNone) {
  KittiLabel raw;  // KITTI raw here: only z
  raw.z = 31.05f;
  EXPECT_FLOAT_EQ(labelNearestDepth(raw), 31.05f);
  KittiLabel none;  // default z = -1000
  EXPECT_FLOAT_EQ(labelNearestDepth(none), 0.0f);
  none.z = NAN;
  EXPECT_FLOAT_EQ(labelNearestDepth(none), 0.0f);
}

TEST(toolsDistanceAccuracy, OnlyFullyVisibleObjectsAreCompared) {
  KittiLabel car = box3d(0, 20, 4, 1.8f, 0);
  EXPECT_TRUE(labelDepthComparable(car));
  car.truncated = 0.3f;  // its nearest corner may be outside the image
  EXPECT_FALSE(labelDepthComparable(car));
  car.truncated = 0;
  car.occluded = 1;      // ... or behind the occluder
  EXPECT_FALSE(labelDepthComparable(car));
  KittiLabel none;
  EXPECT_FALSE(labelDepthComparable(none));
}

TEST(toolsDistanceAccuracy, BandsSummariseBiasMedianAndTail) {
  DistanceAccuracy a;
  // 0-10 m: errors +0.1, -0.3, +0.2 at 5 m
  a.add(5, 5.1f);
  a.add(5, 4.7f);
  a.add(5, 5.2f);
  // 20-30 m: one error of +2 at 25 m
  a.add(25, 27);
  // not counted: non-positive or non-finite values
  a.add(0, 3);
  a.add(8, NAN);
  a.add(-1, 2);
  EXPECT_EQ(a.count(), 4);
  const auto bands = a.bands({0, 10, 20, 30, 40});
  ASSERT_EQ(bands.size(), 2u);  // 10-20 and the empty far bands are left out
  EXPECT_FLOAT_EQ(bands[0].from_m, 0);
  EXPECT_FLOAT_EQ(bands[0].to_m, 10);
  EXPECT_EQ(bands[0].count, 3);
  EXPECT_NEAR(bands[0].bias_m, (0.1 - 0.3 + 0.2) / 3, 1e-5);
  EXPECT_NEAR(bands[0].median_abs_m, 0.2, 1e-5);
  EXPECT_NEAR(bands[0].p95_abs_m, 0.3, 1e-5);
  EXPECT_NEAR(bands[0].median_rel, 0.04, 1e-5);
  EXPECT_EQ(bands[1].count, 1);
  EXPECT_FLOAT_EQ(bands[1].from_m, 20);
  EXPECT_NEAR(bands[1].bias_m, 2.0, 1e-5);
  EXPECT_NEAR(bands[1].median_rel, 0.08, 1e-5);
  // The last edge opens a band to infinity.
  DistanceAccuracy far;
  far.add(55, 50);
  const auto fb = far.bands({0, 40});
  ASSERT_EQ(fb.size(), 1u);
  EXPECT_TRUE(std::isinf(fb[0].to_m));
  EXPECT_NE(formatDistanceBands(fb).find("40+ m"), std::string::npos);
}

TEST(toolsDistanceAccuracy, ErrorsAgainstTheEstimatesOwnSigma) {
  DistanceAccuracy a;
  // At 10 m, sigma 0.2 m: errors 0.1 (0.5 sigma), 0.3 (1.5), 0.5 (2.5), 0.2 (1.0 exactly: within).
  a.add(10, 10.1f, 0.2f);
  a.add(10, 9.7f, 0.2f);
  a.add(10, 10.5f, 0.2f);
  a.add(10, 10.2f, 0.2f);
  // Without a sigma (0, negative, not finite): in the error bands, not in the sigma shares.
  a.add(10, 10.4f, 0);
  a.add(10, 10.4f, -1);
  a.add(10, 10.4f, NAN);
  const auto bands = a.bands({0, 20});
  ASSERT_EQ(bands.size(), 1u);
  EXPECT_EQ(bands[0].count, 7);
  EXPECT_EQ(bands[0].count_with_sigma, 4);
  EXPECT_NEAR(bands[0].within_1sigma, 0.5, 1e-9);
  EXPECT_NEAR(bands[0].within_2sigma, 0.75, 1e-9);
  // |err| / sigma sorted 0.5, 1.0, 1.5, 2.5: the 68th percentile is the third (index 0.68 * 3 -> 2).
  EXPECT_NEAR(bands[0].p68_abs_over_sigma, 1.5, 1e-5);
  const std::string text = formatDistanceBands(bands);
  EXPECT_NE(text.find("within 1 / 2 sigma  50 /  75 %  |err|/sigma p68 1.50"), std::string::npos) << text;
  // No sigma at all: no sigma line.
  DistanceAccuracy none;
  none.add(10, 10.4f);
  EXPECT_EQ(none.bands({0})[0].count_with_sigma, 0);
  EXPECT_EQ(formatDistanceBands(none.bands({0})).find("sigma"), std::string::npos);
  // One band over every range is printed as "all".
  EXPECT_NE(formatDistanceBands(a.bands({0})).find("all"), std::string::npos);
}

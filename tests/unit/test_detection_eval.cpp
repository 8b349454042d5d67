#include <gtest/gtest.h>

#include "detection_eval.hpp"

using namespace nerv;

namespace {
KittiLabel label(const char* type, float x1, float y1, float x2, float y2, float z = 10) {
  KittiLabel l;
  l.type = type;
  l.x1 = x1; l.y1 = y1; l.x2 = x2; l.y2 = y2;
  l.z = z;
  return l;
}
}  // namespace

TEST(toolsDetectionEval, IouByHand) {
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.f);
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {5, 0, 15, 10}), 50.f / 150.f);
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {20, 20, 30, 30}), 0.f);
}

TEST(toolsDetectionEval, TruePositivesMissesAndFalsePositives) {
  const std::vector<KittiLabel> labels = {label("Car", 0, 0, 10, 10), label("Car", 100, 0, 110, 10)};
  // one hit (IoU 0.81), one box in empty space
  const EvalCounts c = evaluateFrame({{0, 0, 9, 9}, {50, 50, 60, 60}}, labels, EvalParams{});
  EXPECT_EQ(c.objects, 2);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fp, 1);
  EXPECT_EQ(c.fn, 1);
  EXPECT_DOUBLE_EQ(c.precision(), 0.5);
  EXPECT_DOUBLE_EQ(c.recall(), 0.5);
}

TEST(toolsDetectionEval, MatchNeedsIouAboveHalf) {
  // IoU 1/3 is no match, IoU 9/11 is
  EXPECT_EQ(evaluateFrame({{5, 0, 15, 10}}, {label("Car", 0, 0, 10, 10)}, EvalParams{}).tp, 0);
  EXPECT_EQ(evaluateFrame({{1, 0, 11, 10}}, {label("Car", 0, 0, 10, 10)}, EvalParams{}).tp, 1);  // 90/110
}

TEST(toolsDetectionEval, SecondBoxOnTheSameObjectIsAFalsePositive) {
  const EvalCounts c = evaluateFrame({{0, 0, 10, 10, 0.9f}, {1, 1, 10, 10, 0.5f}},
                                     {label("Car", 0, 0, 10, 10)}, EvalParams{});
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fp, 1);
  EXPECT_EQ(c.fn, 0);
}

TEST(toolsDetectionEval, DontCareNeitherHitNorMiss) {
  const std::vector<KittiLabel> labels = {label("DontCare", 0, 0, 100, 100)};
  const EvalCounts c = evaluateFrame({{10, 10, 30, 30}, {90, 90, 200, 200}}, labels, EvalParams{});
  EXPECT_EQ(c.objects, 0);
  EXPECT_EQ(c.fn, 0);
  EXPECT_EQ(c.ignored, 1);  // inside the DontCare region
  EXPECT_EQ(c.fp, 1);       // mostly outside it
}

TEST(toolsDetectionEval, FarAndUncountedObjectsAreIgnored) {
  EvalParams p;
  p.max_distance_m = 40;
  p.classes = {"Car"};
  const std::vector<KittiLabel> labels = {label("Car", 0, 0, 10, 10, 60), label("Tram", 50, 0, 60, 10)};
  const EvalCounts c = evaluateFrame({{0, 0, 10, 10}, {50, 0, 60, 10}}, labels, p);
  EXPECT_EQ(c.objects, 0);
  EXPECT_EQ(c.fn, 0);
  EXPECT_EQ(c.fp, 0);
  EXPECT_EQ(c.ignored, 2);
}

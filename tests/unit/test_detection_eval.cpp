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
  // one hit (the label's pixels 0..10 are [0, 11) here: IoU 81/121), one box in empty space
  const EvalCounts c = evaluateFrame({{0, 0, 9, 9}, {50, 50, 60, 60}}, labels, EvalParams{});
  EXPECT_EQ(c.objects, 2);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fp, 1);
  EXPECT_EQ(c.fn, 1);
  EXPECT_DOUBLE_EQ(c.precision(), 0.5);
  EXPECT_DOUBLE_EQ(c.recall(), 0.5);
}

TEST(toolsDetectionEval, MatchNeedsIouAboveHalf) {
  // Label pixels 0..10 = [0, 11) x [0, 11): IoU 60/171 is no match, 100/121 is.
  EXPECT_EQ(evaluateFrame({{5, 0, 15, 10}}, {label("Car", 0, 0, 10, 10)}, EvalParams{}).tp, 0);
  EXPECT_EQ(evaluateFrame({{1, 0, 11, 10}}, {label("Car", 0, 0, 10, 10)}, EvalParams{}).tp, 1);
}

TEST(toolsDetectionEval, LabelBoxesIncludeTheirLastColumnAndRow) {
  // A pole whose pixels are columns 681..687 and rows 190..221 (KITTI: first
  // and last pixel, both included) is 7 x 32 pixels; a detection covering
  // exactly those pixels (x 681, w 7, y 190, h 32 -> [681, 688) x [190, 222)) has IoU 1.
  const KittiLabel pole = label("Pole", 681, 190, 687, 221);
  const EvalBox b = labelBox(pole);
  EXPECT_FLOAT_EQ(b.x2 - b.x1, 7.f);
  EXPECT_FLOAT_EQ(b.y2 - b.y1, 32.f);
  EXPECT_FLOAT_EQ(iou({681, 190, 688, 222}, b), 1.f);
  // One column too far left (680..686): 6 of 8 columns shared, IoU 0.75: a hit.
  EXPECT_FLOAT_EQ(iou({680, 190, 687, 222}, b), 0.75f);
  EXPECT_EQ(evaluateFrame({{680, 190, 687, 222}}, {pole}, EvalParams{}).tp, 1);
  // Two columns of the 7 (IoU 2/7) are no hit.
  EXPECT_EQ(evaluateFrame({{686, 190, 688, 222}}, {pole}, EvalParams{}).tp, 0);
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

TEST(toolsDetectionEval, TheDistanceLimitIgnoresUnmatchedDetectionsBeyondIt) {
  // Labels: a car at 35 m (counted) and one at 45 m (beyond the limit). Boxes:
  // a hit on the 35 m car whose own depth reads 41 m (still a hit), a loose box
  // at 44 m on the far car (IoU 0.25: matches nothing), one at 50 m in empty
  // space, one at 39 m in empty space, and one of unknown depth (0).
  EvalParams p;
  p.max_distance_m = 40;
  const std::vector<KittiLabel> labels = {label("Car", 0, 0, 9, 9, 35), label("Car", 100, 0, 109, 9, 45)};
  std::vector<EvalBox> boxes = {{0, 0, 10, 10}, {105, 0, 115, 10}, {200, 0, 210, 10}, {300, 0, 310, 10},
                                {400, 0, 410, 10}};
  const float z[] = {41, 44, 50, 39, 0};
  for (size_t i = 0; i < boxes.size(); ++i) boxes[i].z = z[i];
  const auto m = matchDetections(boxes, labels, p);
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[0].outcome, MatchOutcome::TruePositive);  // matching comes first, whatever its depth
  EXPECT_EQ(m[1].outcome, MatchOutcome::Ignored);        // beyond 40 m and matching no counted object
  EXPECT_EQ(m[2].outcome, MatchOutcome::Ignored);
  EXPECT_EQ(m[3].outcome, MatchOutcome::FalsePositive);  // within the limit
  EXPECT_EQ(m[4].outcome, MatchOutcome::FalsePositive);  // depth unknown: counted
  const EvalCounts c = countMatches(m, labels, p);
  EXPECT_EQ(c.objects, 1);
  EXPECT_EQ(c.tp, 1);
  EXPECT_EQ(c.fp, 2);
  EXPECT_EQ(c.ignored, 2);
  // The convention before (limit_detections = false): every unmatched box beyond the limit is a false positive.
  p.limit_detections = false;
  const EvalCounts old = evaluateFrame(boxes, labels, p);
  EXPECT_EQ(old.tp, 1);
  EXPECT_EQ(old.fp, 4);
  // Without a limit nothing is beyond it: the far car counts (missed, its box is loose).
  EvalParams none;
  const EvalCounts all = evaluateFrame(boxes, labels, none);
  EXPECT_EQ(all.objects, 2);
  EXPECT_EQ(all.fn, 1);
  EXPECT_EQ(all.fp, 4);
}

TEST(toolsDetectionEval, MatchesNameTheLabelOfEachTruePositive) {
  // detections: a hit on label 1, a box in empty space, one on a DontCare area
  KittiLabel dc = label("DontCare", 200, 0, 240, 40);
  const std::vector<KittiLabel> labels = {label("Car", 0, 0, 10, 10), label("Car", 100, 0, 110, 10), dc};
  const auto m = matchDetections({{100, 0, 111, 11}, {50, 50, 60, 60}, {205, 5, 215, 15}}, labels, EvalParams{});
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].outcome, MatchOutcome::TruePositive);
  EXPECT_EQ(m[0].label, 1);
  EXPECT_EQ(m[1].outcome, MatchOutcome::FalsePositive);
  EXPECT_EQ(m[1].label, -1);
  EXPECT_EQ(m[2].outcome, MatchOutcome::Ignored);
}

TEST(toolsDetectionEval, VisibleOnlyIgnoresHiddenAndTruncatedObjects) {
  KittiLabel hidden = label("Car", 100, 0, 110, 10), cut = label("Car", 200, 0, 210, 10), part = label("Car", 300, 0, 310, 10);
  hidden.occluded = 2;   // largely hidden
  cut.truncated = 0.5f;  // half outside the image
  part.occluded = 1;     // partly hidden: still counted
  const std::vector<KittiLabel> labels = {label("Car", 0, 0, 10, 10), hidden, cut, part};
  const std::vector<EvalBox> boxes = {{0, 0, 10, 10}, {100, 0, 110, 10}, {300, 0, 310, 10}};
  EvalParams all, visible;
  visible.visible_only = true;
  EXPECT_TRUE(isCounted(hidden, all));
  EXPECT_FALSE(isCounted(hidden, visible));
  EXPECT_FALSE(isCounted(cut, visible));
  EXPECT_TRUE(isCounted(part, visible));
  const EvalCounts c_all = evaluateFrame(boxes, labels, all), c_vis = evaluateFrame(boxes, labels, visible);
  EXPECT_EQ(c_all.objects, 4);
  EXPECT_EQ(c_all.tp, 3);
  EXPECT_EQ(c_all.fn, 1);
  // Visible only: the truncated car is no miss, and the box on the hidden one no false positive.
  EXPECT_EQ(c_vis.objects, 2);
  EXPECT_EQ(c_vis.tp, 2);
  EXPECT_EQ(c_vis.fp, 0);
  EXPECT_EQ(c_vis.fn, 0);
  EXPECT_EQ(matchDetections(boxes, labels, visible)[1].outcome, MatchOutcome::Ignored);
}

TEST(toolsDetectionEval, KittiDifficultiesFollowTheDevkitLimits) {
  EvalParams easy, moderate, hard, none;
  EXPECT_EQ(setKittiDifficulty("easy", easy), "");
  EXPECT_EQ(setKittiDifficulty("moderate", moderate), "");
  EXPECT_EQ(setKittiDifficulty("hard", hard), "");
  EXPECT_NE(setKittiDifficulty("medium", none).find("medium"), std::string::npos);
  EXPECT_EQ(none.min_height_px, 0.0f);  // an unknown name leaves the params alone
  EXPECT_EQ(none.difficulty, "");
  EXPECT_EQ(moderate.difficulty, "moderate");
  // Heights as the devkit measures them: y2 - y1 (the last row minus the first).
  const KittiLabel tall = label("Car", 0, 0, 10, 40), low = label("Car", 0, 0, 10, 39), tiny = label("Pole", 0, 0, 2, 24);
  KittiLabel partly = label("Car", 0, 0, 10, 50), largely = partly, cut = partly, unknown = partly;
  partly.occluded = 1;
  largely.occluded = 2;
  unknown.occluded = 3;
  cut.truncated = 0.4f;
  EXPECT_TRUE(isCounted(tall, easy));
  EXPECT_FALSE(isCounted(low, easy));   // 39 px < 40
  EXPECT_TRUE(isCounted(low, moderate));
  EXPECT_FALSE(isCounted(tiny, hard));  // 24 px < 25
  EXPECT_TRUE(isCounted(tiny, none));
  EXPECT_FALSE(isCounted(partly, easy));
  EXPECT_TRUE(isCounted(partly, moderate));
  EXPECT_FALSE(isCounted(largely, moderate));
  EXPECT_TRUE(isCounted(largely, hard));
  EXPECT_FALSE(isCounted(unknown, hard));
  EXPECT_TRUE(isCounted(unknown, none));
  EXPECT_FALSE(isCounted(cut, moderate));  // truncated 0.4 > 0.3
  EXPECT_TRUE(isCounted(cut, hard));
}

TEST(toolsDetectionEval, DetectionsBelowTheMinimumHeightCountOnlyWhenTheyMatch) {
  EvalParams moderate;
  ASSERT_EQ(setKittiDifficulty("moderate", moderate), "");
  const std::vector<KittiLabel> labels = {label("Car", 0, 0, 20, 30), label("Pole", 100, 0, 101, 20)};
  // rows [0, 31) match the car; a 25-row box (y2 - 1 - y1 = 24) in empty space and one on
  // the 21-row pole (ignored: too low) count neither way; a 26-row box in empty space is a
  // false positive
  const std::vector<EvalBox> boxes = {{0, 0, 21, 31}, {50, 0, 60, 25}, {100, 0, 102, 21}, {200, 0, 210, 26}};
  const std::vector<DetectionMatch> m = matchDetections(boxes, labels, moderate);
  EXPECT_EQ(m[0].outcome, MatchOutcome::TruePositive);
  EXPECT_EQ(m[1].outcome, MatchOutcome::Ignored);
  EXPECT_EQ(m[2].outcome, MatchOutcome::Ignored);
  EXPECT_EQ(m[3].outcome, MatchOutcome::FalsePositive);
  const EvalCounts c = countMatches(m, labels, moderate);
  EXPECT_EQ(c.objects, 1);
  EXPECT_EQ(c.fn, 0);
  EXPECT_EQ(c.fp, 1);
  // Without a difficulty the pole is counted and missed, and both boxes in empty space are false positives.
  const EvalCounts all = evaluateFrame(boxes, labels, EvalParams{});
  EXPECT_EQ(all.objects, 2);
  EXPECT_EQ(all.tp, 2);
  EXPECT_EQ(all.fp, 2);
}

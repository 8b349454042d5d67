// Why an object was missed, from the boxes near it: hand-built boxes and depths.
#include <gtest/gtest.h>

#include <cmath>

#include "miss_causes.hpp"

using namespace nerv;

namespace {
// A pedestrian 10 px wide, 20 px tall (label columns 100..109, rows 50..69), nearest depth 20 m.
KittiLabel person() {
  KittiLabel l;
  l.type = "Pedestrian";
  l.x1 = 100, l.y1 = 50, l.x2 = 109, l.y2 = 69;
  l.x = 0, l.y = 1.65f, l.z = 20;  // no 3D size: the labelled depth is its depth
  return l;
}
EvalBox box(float x, float y, float w, float h) { return detectionBox(int(x), int(y), int(w), int(h)); }
}  // namespace

TEST(toolsMissCauses, NoBoxWhenNothingOverlaps) {
  EXPECT_EQ(missCause(person(), {}, {}), MissCause::NoBox);
  EXPECT_EQ(missCause(person(), {box(200, 50, 10, 20)}, {20.0f}), MissCause::NoBox);
}

TEST(toolsMissCauses, LooseBoxAtItsDepth) {
  // The box misses the head: rows 58..69 of 50..69, IoU 12 / 20 = 0.6 would match;
  // rows 62..69 give IoU 0.4 (loose). 21.5 m is within 1.5 m of 20 m.
  const EvalBox loose = box(100, 62, 10, 8);
  ASSERT_NEAR(iou(loose, labelBox(person())), 0.4f, 1e-5);
  EXPECT_EQ(missCause(person(), {loose}, {21.5f}), MissCause::LooseBox);
}

TEST(toolsMissCauses, MergedWhenTheBoxAtItsDepthIsMuchLarger) {
  // The person and the car beside it in one box 40 px wide: IoU 200 / 800 = 0.25.
  const EvalBox merged = box(100, 50, 40, 20);
  ASSERT_NEAR(iou(merged, labelBox(person())), 0.25f, 1e-5);
  EXPECT_EQ(missCause(person(), {merged}, {20.2f}), MissCause::Merged);
  // A well-fitting box at another depth does not make it loose.
  EXPECT_EQ(missCause(person(), {merged, box(100, 62, 10, 8)}, {20.2f, 45.0f}), MissCause::Merged);
}

TEST(toolsMissCauses, PartialWhenTheBoxAtItsDepthIsMuchSmaller) {
  // Only the legs: rows 65..69, IoU 5 / 20 = 0.25.
  const EvalBox legs = box(100, 65, 10, 5);
  ASSERT_NEAR(iou(legs, labelBox(person())), 0.25f, 1e-5);
  EXPECT_EQ(missCause(person(), {legs}, {20.0f}), MissCause::Partial);
  // The better of two boxes at its depth decides: a merged one with IoU 0.25 and a part with 0.15.
  EXPECT_EQ(missCause(person(), {box(100, 67, 10, 3), box(100, 50, 40, 20)}, {20.0f, 20.0f}), MissCause::Merged);
}

TEST(toolsMissCauses, OtherDepthWhenEveryOverlappingBoxIsElsewhere) {
  // The facade 25 m behind, and a nearer occluder; the relative tolerance is 15 % (3 m at 20 m).
  EXPECT_EQ(missCause(person(), {box(90, 20, 40, 60), box(100, 62, 10, 8)}, {45.0f, 16.5f}), MissCause::OtherDepth);
  EXPECT_EQ(missCause(person(), {box(100, 62, 10, 8)}, {17.1f}), MissCause::LooseBox);  // within 3 m
  // A box without a finite depth is at no depth.
  EXPECT_EQ(missCause(person(), {box(100, 62, 10, 8)}, {NAN}), MissCause::OtherDepth);
}

TEST(toolsMissCauses, LabelsWithoutDepthAreJudgedByIoU) {
  KittiLabel l = person();
  l.z = -1000;  // unknown
  EXPECT_EQ(missCause(l, {box(100, 62, 10, 8)}, {45.0f}), MissCause::LooseBox);
  EXPECT_EQ(missCause(l, {box(100, 50, 40, 20)}, {45.0f}), MissCause::Merged);
}

TEST(toolsMissCauses, KeysAreStableIdentifiers) {
  EXPECT_EQ(missCauseKey(MissCause::NoBox), "no_box");
  EXPECT_EQ(missCauseKey(MissCause::OtherDepth), "other_depth");
  EXPECT_EQ(missCauseKey(MissCause::Partial), "part");
  EXPECT_EQ(missCauseKey(MissCause::Merged), "merged");
  EXPECT_EQ(missCauseKey(MissCause::LooseBox), "loose_box");
  EXPECT_EQ(missCauseKey(MissCause::RemovedByValidator), "removed_by_validator");
}

TEST(toolsMissCauses, NamesSayTheThreshold) {
  EXPECT_EQ(missCauseName(MissCause::NoBox), "no box overlaps it");
  EXPECT_EQ(missCauseName(MissCause::LooseBox), "loose box at its depth (IoU >= 0.3)");
  MissCauseParams p;
  p.loose_min_iou = 0.25f;
  EXPECT_EQ(missCauseName(MissCause::Merged, p), "box at its depth, IoU < 0.25, larger (merged)");
  EXPECT_EQ(missCauseName(MissCause::Partial), "box at its depth, IoU < 0.3, smaller (a part)");
}

TEST(toolsMissCauses, TallyCountsOnlyCountedMissesAndNamesTheValidatorsRemovals) {
  KittiLabel far = person();
  far.z = 60;  // beyond max_distance_m: not counted
  KittiLabel dc = person();
  dc.type = "DontCare";
  KittiLabel car = person();
  car.type = "Car";
  car.x1 = 200, car.x2 = 239;
  const std::vector<KittiLabel> labels = {person(), far, dc, car};
  EvalParams ep;
  ep.max_distance_m = 40;
  const std::vector<EvalBox> boxes = {box(200, 50, 40, 20), box(100, 62, 10, 8)};  // the car exactly, a loose one
  const std::vector<float> depth = {20, 20};
  const auto all = matchDetections(boxes, labels, ep);
  const auto kept = matchDetections({box(100, 62, 10, 8)}, labels, ep);  // the validator removed the car's box
  MissTally tally;
  const std::vector<std::string> cause = tally.addFrame(labels, ep, boxes, depth, all, kept);
  ASSERT_EQ(cause.size(), 4u);
  EXPECT_EQ(cause[0], "loose box at its depth (IoU >= 0.3)");
  EXPECT_EQ(cause[1], "");  // not counted
  EXPECT_EQ(cause[2], "");
  EXPECT_EQ(cause[3], "");  // found
  EXPECT_EQ(tally.stixelOnly().size(), 1u);
  EXPECT_EQ(tally.stixelOnly().at(MissCause::LooseBox).at("Pedestrian"), 1);
  EXPECT_EQ(tally.stixelSnv().at(MissCause::RemovedByValidator).at("Car"), 1);
  const std::string text = tally.format();
  EXPECT_NE(text.find("misses by cause (stixel only):\n      1  loose box at its depth (IoU >= 0.3): Pedestrian 1\n"),
            std::string::npos) << text;
  EXPECT_NE(text.find("      1  found by the stixels, removed by the validator: Car 1\n"), std::string::npos) << text;
}

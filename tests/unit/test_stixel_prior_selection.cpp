// Which EXTRINSICS a frame may use as its ground prior (prior_selection.hpp).
#include <gtest/gtest.h>

#include "prior_selection.hpp"

namespace nerv::stixel {
namespace {

GroundPrior pose(float height_m) { return {true, 1.0f, 0.0f, height_m}; }

TEST(stixelPriorSelection, NothingOfferedGivesNoPrior) {
  PriorSelection s;
  EXPECT_FALSE(s.forFrame(0).valid);
  EXPECT_FALSE(s.forFrame(100).valid);
}

TEST(stixelPriorSelection, UsesTheNewestEarlierFrame) {
  PriorSelection s(30);
  s.offer(10, pose(1.5f));
  s.offer(12, pose(1.6f));
  s.offer(11, pose(1.7f));  // out of order (shards)
  EXPECT_FLOAT_EQ(s.forFrame(13).height_m, 1.6f);
  EXPECT_FLOAT_EQ(s.forFrame(12).height_m, 1.7f);  // frame 12's own pose is not earlier
  EXPECT_FLOAT_EQ(s.forFrame(11).height_m, 1.5f);
  EXPECT_FALSE(s.forFrame(10).valid);
}

TEST(stixelPriorSelection, OldPosesAreNotUsed) {
  PriorSelection s(30);
  s.offer(100, pose(1.5f));
  EXPECT_TRUE(s.forFrame(130).valid);
  EXPECT_FALSE(s.forFrame(131).valid);
}

TEST(stixelPriorSelection, ARestartedSourceDoesNotInheritThePreviousDrive) {
  PriorSelection s(1000, 4);
  for (int seq = 500; seq < 504; ++seq) s.offer(seq, pose(2.0f));
  // seq starts again from 0: the old drive's poses are from "later" frames.
  EXPECT_FALSE(s.forFrame(0).valid);
  EXPECT_FALSE(s.forFrame(3).valid);
  s.offer(0, pose(1.2f));
  EXPECT_FLOAT_EQ(s.forFrame(1).height_m, 1.2f);
  // The new drive's poses push the old ones out of the ring.
  for (int seq = 1; seq < 4; ++seq) s.offer(seq, pose(1.3f));
  EXPECT_FLOAT_EQ(s.forFrame(4).height_m, 1.3f);
  EXPECT_FLOAT_EQ(s.forFrame(1).height_m, 1.2f);
  // 500..503 have left the ring (capacity 4): frame 504 gets the new drive's newest.
  EXPECT_FLOAT_EQ(s.forFrame(504).height_m, 1.3f);
}

TEST(stixelPriorSelection, InvalidPosesAreIgnoredAndRepeatsReplace) {
  PriorSelection s(30);
  s.offer(5, GroundPrior{});
  EXPECT_FALSE(s.forFrame(6).valid);
  s.offer(5, pose(1.4f));
  s.offer(5, pose(1.45f));
  EXPECT_FLOAT_EQ(s.forFrame(6).height_m, 1.45f);
}

}  // namespace
}  // namespace nerv::stixel

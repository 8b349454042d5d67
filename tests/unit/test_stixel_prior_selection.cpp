// Which EXTRINSICS a frame may use as its ground prior (prior_selection.hpp).
#include <gtest/gtest.h>

#include <limits>

#include "prior_selection.hpp"

namespace nerv::stixel {
namespace {

GroundPrior pose(float height_m) { return {true, 1.0f, 0.0f, height_m}; }

// Capture time of frame seq of one drive at 10 Hz [us].
int64_t t(int64_t seq) { return 1'700'000'000'000'000 + seq * 100'000; }

TEST(stixelPriorSelection, NothingOfferedGivesNoPrior) {
  PriorSelection s;
  EXPECT_FALSE(s.forFrame(0, t(0)).valid);
  EXPECT_FALSE(s.forFrame(100, t(100)).valid);
}

TEST(stixelPriorSelection, UsesTheNewestEarlierFrame) {
  PriorSelection s(30);
  s.offer(10, t(10), pose(1.5f));
  s.offer(12, t(12), pose(1.6f));
  s.offer(11, t(11), pose(1.7f));  // out of order (shards)
  EXPECT_FLOAT_EQ(s.forFrame(13, t(13)).height_m, 1.6f);
  EXPECT_FLOAT_EQ(s.forFrame(12, t(12)).height_m, 1.7f);  // frame 12's own pose is not earlier
  EXPECT_FLOAT_EQ(s.forFrame(11, t(11)).height_m, 1.5f);
  EXPECT_FALSE(s.forFrame(10, t(10)).valid);
}

TEST(stixelPriorSelection, OldPosesAreNotUsed) {
  PriorSelection s(30);
  s.offer(100, t(100), pose(1.5f));
  EXPECT_TRUE(s.forFrame(130, t(130)).valid);
  EXPECT_FALSE(s.forFrame(131, t(131)).valid);
}

TEST(stixelPriorSelection, ARestartedSourceDoesNotInheritThePreviousDrive) {
  PriorSelection s(1000, 0, 4);  // no limit in time: the seqs alone
  for (int seq = 500; seq < 504; ++seq) s.offer(seq, t(seq), pose(2.0f));
  // seq starts again from 0: the old drive's poses are from "later" frames.
  EXPECT_FALSE(s.forFrame(0, t(0)).valid);
  EXPECT_FALSE(s.forFrame(3, t(3)).valid);
  s.offer(0, t(0), pose(1.2f));
  EXPECT_FLOAT_EQ(s.forFrame(1, t(1)).height_m, 1.2f);
  // The new drive's poses push the old ones out of the ring.
  for (int seq = 1; seq < 4; ++seq) s.offer(seq, t(seq), pose(1.3f));
  EXPECT_FLOAT_EQ(s.forFrame(4, t(4)).height_m, 1.3f);
  EXPECT_FLOAT_EQ(s.forFrame(1, t(1)).height_m, 1.2f);
  // 500..503 have left the ring (capacity 4): frame 504 gets the new drive's newest.
  EXPECT_FLOAT_EQ(s.forFrame(504, t(504)).height_m, 1.3f);
}

TEST(stixelPriorSelection, AShortEarlierDriveIsNotUsedForTheSameSeqsOfTheNext) {
  // A 3-frame replay, then a new drive a minute later counting 0, 1, 2 again:
  // its frame 2 must not take the earlier drive's pose of frame 1.
  PriorSelection s(30, 3'000'000);
  for (int seq = 0; seq < 3; ++seq) s.offer(seq, t(seq), pose(2.0f));
  const int64_t minute = 60'000'000;
  EXPECT_FALSE(s.forFrame(2, t(2) + minute).valid);
  s.offer(0, t(0) + minute, pose(1.2f));  // the new drive's own pose replaces seq 0
  EXPECT_FLOAT_EQ(s.forFrame(1, t(1) + minute).height_m, 1.2f);
  // Seqs 1 and 2 are still the old drive's: frame 3 gets the new drive's seq 0.
  EXPECT_FLOAT_EQ(s.forFrame(3, t(3) + minute).height_m, 1.2f);
  // Within the limit the pose of an earlier frame is used, also 3 s back exactly.
  PriorSelection near(30, 3'000'000);
  near.offer(10, t(10), pose(1.5f));
  EXPECT_TRUE(near.forFrame(40, t(10) + 3'000'000).valid);
  EXPECT_FALSE(near.forFrame(40, t(10) + 3'000'001).valid);
  // A pose captured after the frame (clocks of another drive) is not used.
  EXPECT_FALSE(near.forFrame(11, t(10) - 1).valid);
  // Far-apart times do not wrap into range.
  PriorSelection far(30, 3'000'000);
  far.offer(12, std::numeric_limits<int64_t>::min(), pose(1.7f));
  EXPECT_FALSE(far.forFrame(13, std::numeric_limits<int64_t>::max()).valid);
  PriorSelection later(30, 3'000'000);
  later.offer(14, std::numeric_limits<int64_t>::max(), pose(1.8f));
  EXPECT_FALSE(later.forFrame(15, std::numeric_limits<int64_t>::min()).valid);
}

TEST(stixelPriorSelection, InvalidPosesAreIgnoredAndRepeatsReplace) {
  PriorSelection s(30);
  s.offer(5, t(5), GroundPrior{});
  EXPECT_FALSE(s.forFrame(6, t(6)).valid);
  s.offer(5, t(5), pose(1.4f));
  s.offer(5, t(5), pose(1.45f));
  EXPECT_FLOAT_EQ(s.forFrame(6, t(6)).height_m, 1.45f);
}

}  // namespace
}  // namespace nerv::stixel

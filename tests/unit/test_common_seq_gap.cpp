// SeqGapTracker against a reference that sees the whole stream at once: a seq between
// the first and the last one that never arrived is lost, whatever the arrival order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "seq_gap_tracker.hpp"

using nerv::SeqGapTracker;

namespace {

// Seqs after the first arrival (the receiver cannot know of earlier ones) up to the
// newest that never arrived.
int64_t referenceLost(const std::vector<int64_t>& arrivals) {
  const std::set<int64_t> seen(arrivals.begin(), arrivals.end());
  int64_t lost = 0;
  for (int64_t s = arrivals.front() + 1; s <= *seen.rbegin(); ++s) lost += !seen.count(s);
  return lost;
}

}  // namespace

TEST(commonSeqGap, InOrderGapsAreLostOnceOverdue) {
  SeqGapTracker t(4);
  EXPECT_EQ(t.note(0), 0);
  EXPECT_EQ(t.note(1), 0);
  EXPECT_EQ(t.note(3), 0);  // 2 is missing, not yet overdue
  EXPECT_EQ(t.pending(), 1);
  EXPECT_EQ(t.note(4), 0);
  EXPECT_EQ(t.note(5), 0);
  EXPECT_EQ(t.note(6), 1);  // four newer than 2: lost
  EXPECT_EQ(t.pending(), 0);
}

TEST(commonSeqGap, ShardsSwappingFramesLoseNothing) {
  // Two shards: every pair arrives swapped (1, 0, 3, 2, ...). The old counter called
  // this a loss twice per pair.
  SeqGapTracker t;
  int64_t lost = 0;
  for (int64_t pair = 0; pair < 55; ++pair) {
    lost += t.note(2 * pair + 1);
    lost += t.note(2 * pair);
  }
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(t.pending(), 0);
}

TEST(commonSeqGap, MatchesTheReferenceOnShuffledStreamsWithLosses) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int window = 8;
    // A stream of 300 seqs, each displaced by less than the window, some lost.
    std::vector<std::pair<double, int64_t>> keyed;
    std::uniform_real_distribution<double> jitter(0.0, window - 1.0);
    std::bernoulli_distribution lose(0.05);
    for (int64_t s = 0; s < 300; ++s)
      if (s == 0 || s == 299 || !lose(rng)) keyed.push_back({s + jitter(rng), s});
    std::sort(keyed.begin(), keyed.end());
    std::vector<int64_t> arrivals;
    for (const auto& k : keyed) arrivals.push_back(k.second);
    SeqGapTracker t(window);
    int64_t lost = 0;
    for (int64_t s : arrivals) lost += t.note(s);
    // Every loss is counted once the stream has moved a window past it.
    EXPECT_EQ(lost + t.pending(), referenceLost(arrivals)) << "trial " << trial;
    int64_t flushed = lost;
    for (int64_t s = 300; s < 300 + window; ++s) flushed += t.note(s);
    EXPECT_EQ(flushed, referenceLost(arrivals)) << "trial " << trial;
  }
}

TEST(commonSeqGap, RestartsAndReplaysAreNotLosses) {
  SeqGapTracker t(4);
  for (int64_t s = 0; s < 110; ++s) EXPECT_EQ(t.note(s), 0);
  EXPECT_EQ(t.note(0), 0);  // a replay from the start
  EXPECT_EQ(t.note(1), 0);
  for (int64_t s = 2; s < 110; ++s) EXPECT_EQ(t.note(s), 0);
  EXPECT_EQ(t.note(110), 0);  // the replay runs on past the newest seq
  EXPECT_EQ(t.note(5000), 0);  // a source restarted far ahead
  EXPECT_EQ(t.note(5001), 0);
  EXPECT_EQ(t.note(5001), 0);  // a duplicate
  EXPECT_EQ(t.note(5003), 0);
  EXPECT_EQ(t.note(5004), 0);
  EXPECT_EQ(t.note(5005), 0);
  EXPECT_EQ(t.note(5006), 1);  // 5002 never came
  EXPECT_EQ(t.note(3), 0);     // a restart far back
  EXPECT_EQ(t.note(4), 0);
}

TEST(commonSeqGap, AVeryLateMessageCausesNoFalseLosses) {
  // 20 seqs late with a window of 4: counted lost when it was overdue, and what came
  // after it is not counted again.
  SeqGapTracker t(4);
  int64_t lost = 0;
  for (int64_t s = 0; s <= 100; ++s)
    if (s != 80) lost += t.note(s);
  EXPECT_EQ(lost, 1);
  EXPECT_EQ(t.note(80), 0);
  for (int64_t s = 101; s < 140; ++s) lost += t.note(s);
  EXPECT_EQ(lost, 1);
}

// PartnerPresence (partner_presence.hpp): absent after the given number of frames in a
// row expired without their partner, present again with the next partner message,
// and a partner for a frame already sent alone is recognised as late, once; and
// PartnerJoin (partner_join.hpp), which the validator and snv_extrinsic build on it.
#include <gtest/gtest.h>

#include "partner_join.hpp"
#include "partner_presence.hpp"
#include "seq_join.hpp"

#include <optional>
#include <string>
#include <vector>

using namespace nerv;

TEST(commonPartnerPresence, AbsentAfterFramesInARowWithoutPartner) {
  PartnerPresence p(2);
  EXPECT_FALSE(p.absent());
  p.missed();
  EXPECT_FALSE(p.absent()) << "one lost message is not a stage down";
  EXPECT_TRUE(p.arrived(5));
  p.missed();
  EXPECT_FALSE(p.absent()) << "an arrival in between starts the count again";
  p.missed();
  EXPECT_TRUE(p.absent());
  EXPECT_TRUE(p.arrived(9));
  EXPECT_FALSE(p.absent()) << "present again with the next partner message";
}

TEST(commonPartnerPresence, FramesWaitUntilThePartnerIsAbsent) {
  PartnerPresence p(1);
  EXPECT_FALSE(p.goesAlone(1));
  p.missed();
  EXPECT_TRUE(p.goesAlone(2));
  EXPECT_TRUE(p.goesAlone(3));
  EXPECT_TRUE(p.arrived(4));
  EXPECT_FALSE(p.goesAlone(5)) << "the partner is back: wait for it again";
}

TEST(commonPartnerPresence, APartnerForAFrameSentAloneIsLateOnce) {
  PartnerPresence p(1);
  p.missed();
  ASSERT_TRUE(p.absent());
  ASSERT_TRUE(p.goesAlone(10));
  ASSERT_TRUE(p.goesAlone(11));
  EXPECT_FALSE(p.arrived(10)) << "frame 10 went out alone already";
  EXPECT_FALSE(p.absent());
  EXPECT_TRUE(p.arrived(10)) << "only once";
  EXPECT_FALSE(p.arrived(11));
  EXPECT_TRUE(p.arrived(12));
}

TEST(commonPartnerPresence, ARestartedCountIsANewFrameNotALatePartner) {
  PartnerPresence p(1);
  p.missed();
  ASSERT_TRUE(p.goesAlone(3));  // frame 3 of the first drive, alone
  EXPECT_TRUE(p.arrived(20));   // the partner is back
  EXPECT_FALSE(p.goesAlone(3)); // the source restarted: a new frame 3 waits for its partner
  EXPECT_TRUE(p.arrived(3)) << "and its partner joins it, not taken for late";
}

TEST(commonPartnerPresence, APartnerAfterItsFrameExpiredIsLate) {
  PartnerPresence p(2);
  p.missed();
  p.wentAlone(7);  // waited in vain, went on alone
  EXPECT_FALSE(p.absent());
  EXPECT_FALSE(p.arrived(7)) << "it came after all: late, not a new join";
  EXPECT_TRUE(p.arrived(8));
}

TEST(commonPartnerPresence, RemembersOnlyTheLatestFramesSentAlone) {
  PartnerPresence p(1);
  p.missed();
  for (int64_t s = 0; s < 1000; ++s) ASSERT_TRUE(p.goesAlone(s));
  EXPECT_TRUE(p.arrived(0)) << "forgotten: memory stays bounded";
  EXPECT_FALSE(p.arrived(999));
}

TEST(commonSeqJoin, ExpireAllHandsOverEveryPendingEntryOldestFirst) {
  std::vector<int> expired, matched;
  SeqJoin<int, int> join(
      16, 1000000, [&](const int& a, const int&) { matched.push_back(a); },
      [&](const std::optional<int>& a, const std::optional<int>& b) { expired.push_back(a ? *a : -*b); });
  join.pushA(3, 3, 0);
  join.pushA(1, 1, 0);
  join.pushB(2, 2, 0);
  join.pushA(4, 4, 0);
  join.pushB(4, 4, 0);
  EXPECT_EQ(matched, std::vector<int>({4}));
  join.expireAll();
  EXPECT_EQ(expired, std::vector<int>({1, -2, 3}));
  EXPECT_EQ(join.pending(), 0u);
}

namespace {

struct Msg {
  struct {
    int64_t seq = 0;
  } header;
};

Msg msg(int64_t seq) {
  Msg m;
  m.header.seq = seq;
  return m;
}

}  // namespace

TEST(commonPartnerJoin, RoutesEveryFrameOnceAndStopsWaitingWhileThePartnerIsAbsent) {
  std::vector<std::string> log;
  PartnerJoin<Msg, Msg> join(
      8, 1000, 2,
      {[&](const Msg& a, const Msg&) { log.push_back("matched " + std::to_string(a.header.seq)); },
       [&](const Msg& a, Alone why) {
         log.push_back(std::string(why == Alone::Waited ? "waited " : why == Alone::Flushed ? "flushed " : "at once ") +
                       std::to_string(a.header.seq));
       },
       [&](const Msg& b) { log.push_back("late " + std::to_string(b.header.seq)); },
       [&](const Msg& b) { log.push_back("orphan " + std::to_string(b.header.seq)); }});
  join.pushA(1, msg(1), 0);
  join.pushB(1, msg(1), 0);
  join.pushA(2, msg(2), 0);
  join.pushA(3, msg(3), 500);
  join.tick(1500);  // 2 waited in vain: one miss, the partner is not absent yet
  join.pushA(4, msg(4), 1600);
  join.tick(2000);  // 3 waited in vain too: absent, and 4, still waiting, goes on now
  join.pushA(5, msg(5), 2100);  // does not wait at all
  join.pushB(4, msg(4), 2200);  // 4 went on alone: late; the partner is back
  join.pushA(6, msg(6), 2300);
  join.pushB(6, msg(6), 2300);
  join.pushB(7, msg(7), 2400);
  join.tick(4000);  // 7 never got its first half
  EXPECT_EQ(log, std::vector<std::string>({"matched 1", "waited 2", "waited 3", "flushed 4", "at once 5", "late 4",
                                           "matched 6", "orphan 7"}));
}

TEST(commonPartnerPresence, AStageThatStartsIsExpectedBeforeItsFirstMessage) {
  PartnerPresence p(2);
  EXPECT_FALSE(p.expect()) << "present already: nothing changes";
  p.missed();
  p.missed();
  ASSERT_TRUE(p.goesAlone(4));
  EXPECT_TRUE(p.expect()) << "it was absent";
  EXPECT_FALSE(p.absent());
  EXPECT_FALSE(p.goesAlone(5)) << "the next frame waits for the stage that started";
  EXPECT_TRUE(p.arrived(5));
  EXPECT_FALSE(p.arrived(4)) << "what went alone before it started stays late";
}

// A stage in a crash loop announces itself at each restart and never answers: frames wait for
// it after the first start only, not at every restart.
TEST(commonPartnerPresence, AStageThatStartsAndNeverAnswersIsExpectedOnce) {
  PartnerPresence p(2);
  p.missed();
  p.missed();
  ASSERT_TRUE(p.absent());
  EXPECT_TRUE(p.expect()) << "first start: wait for it";
  EXPECT_FALSE(p.goesAlone(1));
  p.missed();
  p.missed();  // it crashed before its first message
  ASSERT_TRUE(p.absent());
  EXPECT_FALSE(p.expect()) << "started again without having answered: frames go on at once";
  EXPECT_TRUE(p.absent());
  EXPECT_TRUE(p.goesAlone(2));
  EXPECT_TRUE(p.arrived(3)) << "it answers after all";
  p.missed();
  p.missed();
  EXPECT_TRUE(p.expect()) << "having answered, its next start is waited for again";
}

// The validator while snv_extrinsic restarts: without expectPartner, the frames in flight
// while it starts went on alone and their normals came late (2 frames unvalidated).
TEST(commonPartnerJoin, FramesAfterThePartnerStartedWaitForIt) {
  std::vector<std::string> log;
  PartnerJoin<Msg, Msg> join(
      8, 1000, 2,
      {[&](const Msg& a, const Msg&) { log.push_back("matched " + std::to_string(a.header.seq)); },
       [&](const Msg& a, Alone why) {
         log.push_back(std::string(why == Alone::NotWaiting ? "at once " : "alone ") + std::to_string(a.header.seq));
       },
       [&](const Msg& b) { log.push_back("late " + std::to_string(b.header.seq)); },
       [&](const Msg& b) { log.push_back("orphan " + std::to_string(b.header.seq)); }});
  join.pushA(1, msg(1), 0);
  join.pushA(2, msg(2), 0);
  join.tick(1500);             // both waited in vain: the partner is absent
  join.pushA(3, msg(3), 1600);  // at once
  EXPECT_TRUE(join.expectPartner());  // its stage announced itself
  join.pushA(4, msg(4), 1700);  // waits
  join.pushB(4, msg(4), 1750);
  join.pushA(5, msg(5), 1800);
  join.pushB(5, msg(5), 1850);
  EXPECT_EQ(log, std::vector<std::string>({"alone 1", "alone 2", "at once 3", "matched 4", "matched 5"}));
}

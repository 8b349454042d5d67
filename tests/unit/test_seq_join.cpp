#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "seq_join.hpp"

using nerv::SeqJoin;

TEST(commonSeqJoin, MatchesBySeqInAnyOrder) {
  std::vector<std::string> matched;
  int expired = 0;
  SeqJoin<int, std::string> join(
      4, 1000000, [&](const int& a, const std::string& b) { matched.push_back(std::to_string(a) + b); },
      [&](auto&, auto&) { ++expired; });
  join.pushA(1, 10, 0);
  join.pushB(2, "y", 0);
  join.pushB(1, "x", 0);
  join.pushA(2, 20, 0);
  EXPECT_EQ(matched, (std::vector<std::string>{"10x", "20y"}));
  EXPECT_EQ(expired, 0);
  EXPECT_EQ(join.pending(), 0u);
}

TEST(commonSeqJoin, BoundedBufferHandsOutTheOldest) {
  std::vector<long> expired_a;
  SeqJoin<long, long> join(
      2, 1000000, [](const long&, const long&) {},
      [&](const std::optional<long>& a, const std::optional<long>& b) {
        ASSERT_TRUE(a.has_value());
        EXPECT_FALSE(b.has_value());
        expired_a.push_back(*a);
      });
  for (long s = 0; s < 5; ++s) join.pushA(s, s * 100, 0);
  EXPECT_EQ(expired_a, (std::vector<long>{0, 100, 200}));
  EXPECT_EQ(join.pending(), 2u);
}

TEST(commonSeqJoin, ExpiresByAge) {
  int expired = 0;
  SeqJoin<int, int> join(10, 500, [](const int&, const int&) {}, [&](auto&, auto&) { ++expired; });
  join.pushB(7, 1, 1000);
  join.expire(1400);
  EXPECT_EQ(expired, 0);
  join.expire(1600);
  EXPECT_EQ(expired, 1);
  EXPECT_EQ(join.pending(), 0u);
}

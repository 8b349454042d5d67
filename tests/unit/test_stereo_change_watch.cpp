// When a noisy rig reading says the rig changed since the last verdict
// (services/stereo_matcher/change_watch.hpp): a reading clearly on the other side of the limit
// (by a margin of 1.25) is suspect, two in a row are a change, and nothing more is said until
// the next verdict.
#include <gtest/gtest.h>

#include "change_watch.hpp"

namespace nerv::stereo {
namespace {

using Step = ChangeWatch::Step;
constexpr float kLimit = 2.0f;  // e.g. max_view_delay_ms

TEST(stereoChangeWatch, NothingBeforeTheFirstVerdict) {
  ChangeWatch w;
  EXPECT_EQ(w.reading(5.0f, kLimit), Step::Nothing);
  EXPECT_EQ(w.reading(5.0f, kLimit), Step::Nothing);
}

TEST(stereoChangeWatch, TwoReadingsInARowAgainstTheVerdictAreAChange) {
  ChangeWatch w;
  w.verdict(false, 0.3f);
  EXPECT_EQ(w.reading(1.0f, kLimit), Step::Nothing);
  EXPECT_EQ(w.reading(5.6f, kLimit), Step::Confirm);
  EXPECT_EQ(w.reading(-5.2f, kLimit), Step::Restart) << "either way";
  EXPECT_FLOAT_EQ(w.suspectValue(), 5.6f);
  EXPECT_FLOAT_EQ(w.verdictValue(), 0.3f);
  EXPECT_EQ(w.reading(5.0f, kLimit), Step::Nothing) << "watched already: nothing until the verdict";
  EXPECT_EQ(w.reading(0.0f, kLimit), Step::Nothing);
  EXPECT_EQ(w.reading(5.0f, kLimit), Step::Nothing);
  w.verdict(true, 5.3f);  // the verdict of the readings since
  EXPECT_EQ(w.reading(5.1f, kLimit), Step::Nothing) << "in line with the new verdict";
  EXPECT_EQ(w.reading(0.2f, kLimit), Step::Confirm) << "mended: the same the other way";
  EXPECT_EQ(w.reading(0.1f, kLimit), Step::Restart);
}

// A rig near its limit reads on both sides of it: only readings clearly across count, beyond
// 1.25 times the limit after a verdict within it, under the limit / 1.25 after one beyond it.
TEST(stereoChangeWatch, ReadingsNearTheLimitAreNotAChange) {
  ChangeWatch within;
  within.verdict(false, 1.9f);
  EXPECT_EQ(within.reading(2.4f, kLimit), Step::Nothing);
  EXPECT_EQ(within.reading(2.45f, kLimit), Step::Nothing);
  EXPECT_EQ(within.reading(2.6f, kLimit), Step::Confirm);
  ChangeWatch beyond;
  beyond.verdict(true, 2.2f);
  EXPECT_EQ(beyond.reading(1.7f, kLimit), Step::Nothing);
  EXPECT_EQ(beyond.reading(1.5f, kLimit), Step::Confirm);
}

TEST(stereoChangeWatch, AnOddReadingBetweenGoodOnesIsForgotten) {
  ChangeWatch w;
  w.verdict(false, 0.1f);
  EXPECT_EQ(w.reading(2.6f, kLimit), Step::Confirm);
  EXPECT_EQ(w.reading(0.4f, kLimit), Step::Nothing);
  EXPECT_EQ(w.reading(2.6f, kLimit), Step::Confirm) << "suspect again, not a change";
  w.verdict(false, 0.2f);
  EXPECT_EQ(w.reading(2.6f, kLimit), Step::Confirm) << "a verdict forgets the suspect reading";
}

}  // namespace
}  // namespace nerv::stereo

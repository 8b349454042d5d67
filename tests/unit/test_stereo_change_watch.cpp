// When a noisy rig reading says the rig changed since the last verdict
// (services/stereo_matcher/change_watch.hpp): one reading against the verdict is suspect, two
// in a row are a change, and nothing more is said until the next verdict.
#include <gtest/gtest.h>

#include "change_watch.hpp"

namespace nerv::stereo {
namespace {

using Step = ChangeWatch::Step;

TEST(stereoChangeWatch, NothingBeforeTheFirstVerdict) {
  ChangeWatch w;
  EXPECT_EQ(w.reading(true, 5.0f), Step::Nothing);
  EXPECT_EQ(w.reading(true, 5.0f), Step::Nothing);
}

TEST(stereoChangeWatch, TwoReadingsInARowAgainstTheVerdictAreAChange) {
  ChangeWatch w;
  w.verdict(false, 0.3f);
  EXPECT_EQ(w.reading(false, 1.0f), Step::Nothing);
  EXPECT_EQ(w.reading(true, 5.6f), Step::Confirm);
  EXPECT_EQ(w.reading(true, 5.2f), Step::Restart);
  EXPECT_FLOAT_EQ(w.suspectValue(), 5.6f);
  EXPECT_FLOAT_EQ(w.verdictValue(), 0.3f);
  EXPECT_EQ(w.reading(true, 5.0f), Step::Nothing) << "watched already: nothing until the verdict";
  EXPECT_EQ(w.reading(false, 0.0f), Step::Nothing);
  EXPECT_EQ(w.reading(true, 5.0f), Step::Nothing);
  w.verdict(true, 5.3f);  // the verdict of the readings since
  EXPECT_EQ(w.reading(true, 5.1f), Step::Nothing) << "in line with the new verdict";
  EXPECT_EQ(w.reading(false, 0.2f), Step::Confirm) << "mended: the same the other way";
  EXPECT_EQ(w.reading(false, 0.1f), Step::Restart);
}

TEST(stereoChangeWatch, AnOddReadingBetweenGoodOnesIsForgotten) {
  ChangeWatch w;
  w.verdict(false, 0.1f);
  EXPECT_EQ(w.reading(true, 2.5f), Step::Confirm);
  EXPECT_EQ(w.reading(false, 0.4f), Step::Nothing);
  EXPECT_EQ(w.reading(true, 2.4f), Step::Confirm) << "suspect again, not a change";
  w.verdict(false, 0.2f);
  EXPECT_EQ(w.reading(true, 2.4f), Step::Confirm) << "a verdict forgets the suspect reading";
}

}  // namespace
}  // namespace nerv::stereo

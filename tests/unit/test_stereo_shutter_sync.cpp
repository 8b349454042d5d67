// Were the two views taken together? (services/stereo_matcher/shutter_sync.hpp) On the
// rendered urban street (ego at 8 m/s, 10 frames a second) with the right view rendered
// later or earlier than the left (nerv_synth's --right-delay-ms), and the rig check's verdict.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "rig_check.hpp"
#include "shutter_sync.hpp"
#include "stereo_rendered_pair.hpp"

namespace nerv::stereo {
namespace {

using test::Pair;
using test::renderedPair;

// The delay read [ms] at 10 frames a second.
ShutterSync measure(const Pair& p) {
  return measureShutterSync(p.previous_left, p.left, p.right, p.disparity, p.fx, p.cx, p.cy);
}

TEST(stereoShutterSync, ReadsTheDelayOfRenderedViews) {
  const ShutterSync together = measure(renderedPair(4, 0));
  ASSERT_TRUE(together.valid) << together.points << " points, motion " << together.motion_px << " px";
  EXPECT_GT(together.points, 150);
  // The forward step between the frames, 0.8 m: k = s / (f B) = 0.00205 (f 721.5 px, B 0.54 m).
  EXPECT_NEAR(together.k_motion, 0.8 / (721.5377 * 0.54), 0.0002);
  EXPECT_NEAR(together.offset * 100.0, 0.0, 3.0);
  const ShutterSync late = measure(renderedPair(4, 10));
  ASSERT_TRUE(late.valid);
  EXPECT_NEAR(late.offset * 100.0, 10.0, 4.0);
  const ShutterSync early = measure(renderedPair(4, -10));
  ASSERT_TRUE(early.valid);
  EXPECT_NEAR(early.offset * 100.0, -10.0, 4.0);
}

TEST(stereoShutterSync, StandingStillThereIsNothingToCompare) {
  const Pair& p = renderedPair(4, 10);
  const ShutterSync s = measureShutterSync(p.left, p.left, p.right, p.disparity, p.fx, p.cx, p.cy);
  EXPECT_FALSE(s.valid);
  EXPECT_FALSE(s.moving);
  EXPECT_LT(s.motion_px, 0.5f);
  // Reversing (the frames the other way round): not measured either.
  const ShutterSync back = measureShutterSync(p.left, p.previous_left, p.right, p.disparity, p.fx, p.cx, p.cy);
  EXPECT_FALSE(back.valid);
}

TEST(stereoShutterSync, BadInputsGiveNoMeasurement) {
  const Pair& p = renderedPair(4, 0);
  cv::Mat colour, small;
  cv::cvtColor(p.left, colour, cv::COLOR_GRAY2BGR);
  cv::resize(p.left, small, cv::Size(), 0.5, 0.5);
  EXPECT_FALSE(measureShutterSync(cv::Mat(), p.left, p.right, p.disparity, p.fx, p.cx, p.cy).valid);
  EXPECT_FALSE(measureShutterSync(p.previous_left, colour, p.right, p.disparity, p.fx, p.cx, p.cy).valid);
  EXPECT_FALSE(measureShutterSync(small, p.left, p.right, p.disparity, p.fx, p.cx, p.cy).valid);
  EXPECT_FALSE(measureShutterSync(p.previous_left, p.left, p.right, cv::Mat(), p.fx, p.cx, p.cy).valid);
  EXPECT_FALSE(measureShutterSync(p.previous_left, p.left, p.right, p.disparity, std::nan(""), p.cx, p.cy).valid);
  EXPECT_FALSE(measureShutterSync(p.previous_left, p.left, p.right, p.disparity, p.fx, p.cx, INFINITY).valid);
  const cv::Mat none = cv::Mat::zeros(p.left.size(), CV_32FC1);
  EXPECT_FALSE(measureShutterSync(p.previous_left, p.left, p.right, none, p.fx, p.cx, p.cy).valid);
  const cv::Mat flat(p.left.size(), CV_8UC1, cv::Scalar(90));
  EXPECT_FALSE(measureShutterSync(flat, flat, flat, p.disparity, p.fx, p.cx, p.cy).valid);
}

TEST(stereoShutterSync, VerdictOnTheMedianOfTenDelays) {
  MedianVerdict m(10, 2.0f);
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(m.add(i == 4 ? 40.0f : 0.5f)) << i;
  EXPECT_FALSE(m.add(NAN));
  EXPECT_TRUE(m.add(0.5f));
  EXPECT_FLOAT_EQ(m.median(), 0.5f);
  EXPECT_FALSE(m.beyond());  // one odd reading does not decide
  EXPECT_EQ(describeViewDelay(m),
            "the right view is taken 0.5 ms after the left (median of the last 10 checks while moving, 0.5 to 40.0 ms)");
  for (int i = 0; i < 9; ++i) EXPECT_FALSE(m.add(-4.0f));
  EXPECT_TRUE(m.add(-4.0f));
  EXPECT_TRUE(m.beyond());
  EXPECT_NE(describeViewDelay(m).find("taken 4.0 ms before the left"), std::string::npos) << describeViewDelay(m);
}

// Through the rig check, every frame checked: frames 3 and 4 fed in turn, so every other
// check compares a frame with the one after it (driving backwards: not measured) and the
// others give 10 delays in 20 frames.
std::vector<RigFinding> feed(RigCheck& rig, double delay_ms, int frames, std::string* said) {
  const Pair& b = renderedPair(4, delay_ms);
  const Pair& a = renderedPair(3, delay_ms);
  std::vector<RigFinding> all;
  for (int i = 0; i < frames; ++i) {
    const Pair& p = i % 2 ? b : a;
    const auto found = rig.afterMatching(p.left, p.right, p.disparity, {100000LL * i, p.fx, p.cx, p.cy});
    for (const RigFinding& f : found) {
      all.push_back(f);
      if (said && !f.message.empty()) *said += f.name + ": " + f.message + "\n";
    }
  }
  return all;
}

int count(const std::vector<RigFinding>& found, const std::string& name) {
  int n = 0;
  for (const RigFinding& f : found) n += f.name == name;
  return n;
}

TEST(stereoShutterSync, RigCheckSaysWhenTheViewsAreApart) {
  RigCheckParams every;
  every.check_every = 1;
  RigCheck apart(every);
  std::string said;
  const std::vector<RigFinding> late = feed(apart, 10, 20, &said);
  EXPECT_EQ(count(late, "sync_checks"), 10) << said;
  ASSERT_EQ(count(late, "views_unsynchronised"), 1) << said;
  EXPECT_NE(said.find("views_unsynchronised: shutters: the right view is taken "), std::string::npos) << said;
  EXPECT_NE(said.find(" ms after the left (median of the last 10 checks while moving"), std::string::npos) << said;
  EXPECT_NE(said.find("(max_view_delay_ms 2.0): the cameras are not triggered together"), std::string::npos) << said;
  double delay = NAN;  // the gauge NERV_HEALTH carries
  for (const RigFinding& f : late)
    if (f.kind == RigFinding::Kind::Gauge && f.name == "view_delay_ms") delay = f.value;
  EXPECT_NEAR(delay, 10.0, 3.0);

  RigCheck together(every);
  said.clear();
  const std::vector<RigFinding> same = feed(together, 0, 20, &said);
  EXPECT_EQ(count(same, "sync_checks"), 10) << said;
  EXPECT_EQ(count(same, "views_unsynchronised"), 0) << said;
  EXPECT_NE(said.find("shutter check: the right view is taken "), std::string::npos) << said;
  EXPECT_NE(said.find(": synchronised"), std::string::npos) << said;

  // Without the camera (fx 0) there is no shutter check.
  RigCheck blind(every);
  const Pair& p = renderedPair(4, 10);
  for (int i = 0; i < 20; ++i)
    EXPECT_EQ(count(blind.afterMatching(p.left, p.right, p.disparity, {100000LL * i}), "sync_checks"), 0);
}

}  // namespace
}  // namespace nerv::stereo

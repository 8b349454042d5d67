// Is every disparity off by the same amount? (services/stereo_matcher/disparity_offset.hpp) On
// the rendered urban street (ego at 8 m/s, 10 frames a second) with the right view moved
// sideways by a known amount (as a right camera turned about its vertical axis), and the rig
// check's verdict.
#include <gtest/gtest.h>

#include <cmath>

#include "disparity_offset.hpp"
#include "rig_check.hpp"
#include "stereo_rendered_pair.hpp"

namespace nerv::stereo {
namespace {

using test::Pair;
using test::renderedPair;

DisparityOffset measure(const Pair& p) {
  return measureDisparityOffset(trackMotion(p.previous_left, p.left, p.disparity), p.fx, p.cx, p.cy);
}

TEST(stereoDisparityOffset, ReadsAnOffsetFromTheForwardMotion) {
  const DisparityOffset none = measure(renderedPair(4, 0));
  ASSERT_TRUE(none.valid) << none.points << " points, motion " << none.motion_px << " px";
  EXPECT_GT(none.points, 150);
  EXPECT_NEAR(none.k, 0.8 / (721.5377 * 0.54), 0.0003);  // the 0.8 m step: s / (f B)
  EXPECT_NEAR(none.offset_px, 0.0, 0.4);
  const DisparityOffset more = measure(renderedPair(4, 0, 1.0));
  ASSERT_TRUE(more.valid);
  EXPECT_NEAR(more.offset_px, 1.0, 0.4);
  const DisparityOffset less = measure(renderedPair(4, 0, -1.0));
  ASSERT_TRUE(less.valid);
  EXPECT_NEAR(less.offset_px, -1.0, 0.4);
  EXPECT_GT(more.offset_px - less.offset_px, 1.5);
}

TEST(stereoDisparityOffset, NothingToCompareStandingOrReversingOrWithoutPoints) {
  const Pair& p = renderedPair(4, 0, 1.0);
  EXPECT_FALSE(measureDisparityOffset(trackMotion(p.left, p.left, p.disparity), p.fx, p.cx, p.cy).valid);
  EXPECT_FALSE(measureDisparityOffset(trackMotion(p.left, p.previous_left, p.disparity), p.fx, p.cx, p.cy).valid);
  const MotionTracks tracks = trackMotion(p.previous_left, p.left, p.disparity);
  EXPECT_FALSE(measureDisparityOffset(tracks, 0, p.cx, p.cy).valid);
  EXPECT_FALSE(measureDisparityOffset(tracks, p.fx, NAN, p.cy).valid);
  EXPECT_FALSE(measureDisparityOffset(MotionTracks{}, p.fx, p.cx, p.cy).valid);
  EXPECT_TRUE(trackMotion(p.previous_left, p.left, cv::Mat()).matched.left.empty());
  cv::Mat colour;
  cv::cvtColor(p.left, colour, cv::COLOR_GRAY2BGR);
  EXPECT_TRUE(trackMotion(p.previous_left, colour, p.disparity).matched.left.empty());
}

TEST(stereoDisparityOffset, VerdictWording) {
  MedianVerdict m(10, 0.5f);
  for (int i = 0; i < 10; ++i) m.add(i < 7 ? 0.62f : 0.41f);
  EXPECT_TRUE(m.beyond());
  EXPECT_EQ(describeDisparityOffset(m),
            "the disparity reads 0.62 px more than the forward motion says (median of the last 10 checks while moving, "
            "0.41 to 0.62 px)");
}

// Through the rig check, every frame checked: frames 3 and 4 in turn (every other check is
// driving backwards and not measured), 20 frames for 10 offsets.
TEST(stereoDisparityOffset, RigCheckSaysWhenEveryDisparityIsOff) {
  RigCheckParams every;
  every.check_every = 1;
  every.offset_correction = false;  // the error's own words (corrected: test_stereo_offset_correction.cpp)
  for (const double shift : {0.0, 1.0}) {
    RigCheck rig(every);
    std::string said;
    int checks = 0, errors = 0;
    double gauge = NAN;
    for (int i = 0; i < 20; ++i) {
      const Pair& p = renderedPair(i % 2 ? 4 : 3, 0, shift);
      for (const RigFinding& f : rig.afterMatching(p.left, p.right, p.disparity,
                                                   {100000LL * i, p.fx, p.cx, p.cy, p.baseline_m})) {
        checks += f.name == "offset_checks";
        errors += f.name == "disparity_offset";
        if (f.name == "disparity_offset_px") gauge = f.value;
        if (!f.message.empty()) said += f.name + ": " + f.message + "\n";
      }
    }
    EXPECT_EQ(checks, 10) << said;
    EXPECT_NEAR(gauge, shift, 0.35) << said;
    if (shift == 0) {
      EXPECT_EQ(errors, 0) << said;
      EXPECT_NE(said.find("disparity offset check: the disparity reads "), std::string::npos) << said;
      EXPECT_NE(said.find(": within the limit"), std::string::npos) << said;
    } else {
      EXPECT_EQ(errors, 1) << said;
      EXPECT_NE(said.find("disparity_offset: disparity: the disparity reads "), std::string::npos) << said;
      EXPECT_NE(said.find("px more than the forward motion says"), std::string::npos) << said;
      // 1 px at 40 m with f 721.5 px and B 0.54 m (d 9.7 px): 9 %.
      EXPECT_NE(said.find("(max_disparity_offset_px 0.60): a camera turned about its vertical axis since calibration, "
                          "or the principal points moved; every distance is off, "),
                std::string::npos)
          << said;
      EXPECT_NE(said.find("% at 40 m (objects read nearer); recalibrate the rig"), std::string::npos) << said;
    }
  }
}

}  // namespace
}  // namespace nerv::stereo

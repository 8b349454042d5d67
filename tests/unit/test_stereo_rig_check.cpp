// When the stereo_matcher checks its rig and what it says (services/stereo_matcher/rig_check.hpp).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "rig_check.hpp"
#include "stereo_rig_findings.hpp"
#include "stereo_scene_texture.hpp"

namespace nerv::stereo {
namespace {

cv::Mat texture(unsigned seed) { return multiScaleTexture(640, 240, seed); }

// The right view of a wall at disparity 20, its rows moved by dy.
cv::Mat rightView(const cv::Mat& left, double dy) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -20, 0, 1, dy);
  cv::Mat right;
  cv::warpAffine(left, right, shift, left.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return right;
}

const cv::Mat kWall(240, 640, CV_32FC1, cv::Scalar(20.0f));

// The checks as they were before the row correction: the error paths' own words.
RigCheckParams uncorrected() {
  RigCheckParams p;
  p.row_correction = false;
  return p;
}

TEST(stereoRigCheck, FirstTenFramesThenEveryTenthAndAVerdictEveryTenChecks) {
  RigCheck rig;  // check_every 10, first_checks 10
  const cv::Mat left = texture(1), right = rightView(left, 0);
  for (int frame = 1; frame <= 9; ++frame) EXPECT_EQ(findingNames(rig.afterMatching(left, right, kWall)), "row_checks") << frame;
  const std::vector<RigFinding> tenth = rig.afterMatching(left, right, kWall);
  ASSERT_EQ(findingNames(tenth), "row_checks log");
  EXPECT_EQ(tenth[1].kind, RigFinding::Kind::Log);
  EXPECT_NE(tenth[1].message.find("rectification check: the right view's rows lie"), std::string::npos);
  EXPECT_NE(tenth[1].message.find(": aligned"), std::string::npos);
  for (int frame = 11; frame <= 19; ++frame) EXPECT_EQ(findingNames(rig.afterMatching(left, right, kWall)), "") << frame;
  EXPECT_EQ(findingNames(rig.afterMatching(left, right, kWall)), "row_checks");  // frame 20
  // The 20th check's verdict: still aligned, unchanged, so no second line.
  for (int frame = 21; frame <= 100; ++frame) {
    const std::string said = findingNames(rig.afterMatching(left, right, kWall));
    EXPECT_EQ(said, frame % 10 == 0 ? "row_checks" : "") << frame;
  }
  // check_every 0: no row checks at all.
  RigCheck off({0});
  for (int frame = 1; frame <= 12; ++frame) EXPECT_TRUE(off.afterMatching(left, right, kWall).empty());
}

TEST(stereoRigCheck, RowsOffAreAnErrorAtTheVerdict) {
  RigCheck rig(uncorrected());
  const cv::Mat left = texture(2), right = rightView(left, 1.0);
  for (int frame = 1; frame <= 9; ++frame) rig.afterMatching(left, right, kWall);
  const std::vector<RigFinding> tenth = rig.afterMatching(left, right, kWall);
  ASSERT_EQ(findingNames(tenth), "row_checks row_misaligned");
  EXPECT_EQ(tenth[1].kind, RigFinding::Kind::Error);
  EXPECT_NE(tenth[1].message.find("rectification: the right view's rows lie 1.0"), std::string::npos) << tenth[1].message;
  EXPECT_NE(tenth[1].message.find("(max_row_offset_px 0.40); disparity and detections degrade, recalibrate it"),
            std::string::npos)
      << tenth[1].message;
}

TEST(stereoRigCheck, AStoppedCameraIsSaidAndPausesTheRowChecks) {
  RigCheck rig;
  const cv::Mat stuck = texture(3);
  EXPECT_EQ(findingNames(rig.beforeMatching(texture(10), stuck)), "");
  // Repeated once and twice: not yet said, but no row check while it repeats.
  EXPECT_EQ(findingNames(rig.beforeMatching(texture(11), stuck)), "");
  EXPECT_TRUE(rig.afterMatching(texture(11), stuck, kWall).empty());
  EXPECT_EQ(findingNames(rig.beforeMatching(texture(12), stuck)), "");
  const std::vector<RigFinding> third = rig.beforeMatching(texture(13), stuck);
  ASSERT_EQ(findingNames(third), "frozen_view_frames view_frozen");
  EXPECT_EQ(third[1].message,
            "the right camera's image has not changed for 3 frames while the other's has: a stopped camera or "
            "driver; the disparity compares images taken at different times");
  EXPECT_EQ(findingNames(rig.beforeMatching(texture(14), stuck)), "frozen_view_frames");  // counted; said again at the 100th
  EXPECT_TRUE(rig.afterMatching(texture(14), stuck, kWall).empty());
}

TEST(stereoRigCheck, BlankAndSwappedViewsAreSaidOnTheSecondUnmeasuredCheck) {
  const cv::Mat none = cv::Mat::zeros(240, 640, CV_32FC1);  // the matcher found nothing
  const cv::Mat left = texture(4);
  cv::Mat fogged;
  cv::GaussianBlur(rightView(left, 0), fogged, cv::Size(0, 0), 8);
  RigCheck blank;
  EXPECT_EQ(findingNames(blank.afterMatching(left, fogged, none)), "row_checks_unmeasured");
  const std::vector<RigFinding> second = blank.afterMatching(left, fogged, none);
  ASSERT_EQ(findingNames(second), "row_checks_unmeasured view_blank");
  EXPECT_NE(second[1].message.find("the right view shows almost no texture (0 textured points"), std::string::npos)
      << second[1].message;
  RigCheck swapped;
  const cv::Mat right = rightView(left, 0);
  EXPECT_EQ(findingNames(swapped.afterMatching(right, left, none)), "row_checks_unmeasured");
  const std::vector<RigFinding> again = swapped.afterMatching(right, left, none);
  ASSERT_EQ(findingNames(again), "row_checks_unmeasured views_swapped");
  EXPECT_NE(again[1].message.find("the left and right views look swapped"), std::string::npos);
}

// A rig knocked mid-drive: the first check after it reads the rows off, the checks then run
// on every frame, and the error comes at the tenth of them, not when the old window is outvoted.
TEST(stereoRigCheck, AKnockMidDriveIsSaidWithinTwentyFrames) {
  RigCheck rig(uncorrected());
  const cv::Mat left = texture(5), aligned = rightView(left, 0), knocked = rightView(left, 1.0);
  for (int frame = 1; frame <= 103; ++frame) rig.afterMatching(left, aligned, kWall);
  // Knocked at frame 104: frames 104-109 are not checked; 110 is, and reads it.
  for (int frame = 104; frame <= 109; ++frame) EXPECT_EQ(findingNames(rig.afterMatching(left, knocked, kWall)), "") << frame;
  const std::vector<RigFinding> first = rig.afterMatching(left, knocked, kWall);
  ASSERT_EQ(findingNames(first), "row_checks log row_rechecks");
  EXPECT_NE(first[1].message.find("this frame's rows are up to 1.0"), std::string::npos) << first[1].message;
  EXPECT_NE(first[1].message.find("checking every frame for the next 10 checks"), std::string::npos);
  for (int frame = 111; frame <= 118; ++frame)
    EXPECT_EQ(findingNames(rig.afterMatching(left, knocked, kWall)), "row_checks") << frame;
  const std::vector<RigFinding> verdict = rig.afterMatching(left, knocked, kWall);  // frame 119
  ASSERT_EQ(findingNames(verdict), "row_checks row_misaligned") << verdict.back().message;
  EXPECT_NE(verdict[1].message.find("median of the last 10 checks"), std::string::npos);
  // Back to every tenth frame, and the error again at each verdict while it lasts.
  for (int frame = 120; frame <= 129; ++frame)
    EXPECT_EQ(findingNames(rig.afterMatching(left, knocked, kWall)), frame % 10 == 0 ? "row_checks" : "") << frame;

  // Mended: the same the other way, an "aligned" line ten checks after the first good one.
  for (int frame = 130; frame <= 139; ++frame) rig.afterMatching(left, knocked, kWall);  // the next verdict at 210
  ASSERT_EQ(findingNames(rig.afterMatching(left, aligned, kWall)), "row_checks log row_rechecks");  // frame 140
  for (int frame = 141; frame <= 148; ++frame)
    EXPECT_EQ(findingNames(rig.afterMatching(left, aligned, kWall)), "row_checks") << frame;
  const std::vector<RigFinding> mended = rig.afterMatching(left, aligned, kWall);  // frame 149
  ASSERT_EQ(findingNames(mended), "row_checks log");
  EXPECT_NE(mended[1].message.find(": aligned"), std::string::npos) << mended[1].message;
}

// Each row verdict sets the gauges NERV_HEALTH carries: how far the rows are off, the turn.
TEST(stereoRigCheck, GaugesAtEachVerdict) {
  RigCheck rig;
  const cv::Mat left = texture(7), right = rightView(left, 0.7);
  for (int frame = 1; frame <= 9; ++frame) EXPECT_TRUE(std::isnan(findingGauge(rig.afterMatching(left, right, kWall), "row_offset_px")));
  const std::vector<RigFinding> tenth = rig.afterMatching(left, right, kWall);
  EXPECT_NEAR(findingGauge(tenth, "row_offset_px"), 0.7, 0.05);
  EXPECT_NEAR(findingGauge(tenth, "row_turn_deg"), 0.0, 0.01);
  EXPECT_TRUE(std::isnan(findingGauge(tenth, "view_delay_ms")));  // no timing given: no shutter check
}

// One odd reading (glare, a bump) makes ten checks in a row, whose verdict stands as it was.
TEST(stereoRigCheck, OneOddReadingChangesNothing) {
  RigCheck rig;
  const cv::Mat left = texture(6), aligned = rightView(left, 0), odd = rightView(left, 1.5);
  for (int frame = 1; frame <= 19; ++frame) rig.afterMatching(left, aligned, kWall);
  EXPECT_EQ(findingNames(rig.afterMatching(left, odd, kWall)), "row_checks log row_rechecks");  // frame 20
  for (int frame = 21; frame <= 29; ++frame) {
    const std::string said = findingNames(rig.afterMatching(left, aligned, kWall));
    EXPECT_TRUE(said == "row_checks" || said == "row_checks log") << frame << ": " << said;
    EXPECT_EQ(said.find("row_misaligned"), std::string::npos) << frame;
  }
  for (int frame = 30; frame <= 60; ++frame)
    EXPECT_EQ(findingNames(rig.afterMatching(left, aligned, kWall)), frame % 10 == 0 ? "row_checks" : "") << frame;
}

}  // namespace
}  // namespace nerv::stereo

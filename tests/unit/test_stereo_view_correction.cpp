// The right view resampled by the rows measured off and the disparity offset taken off
// (services/stereo_matcher/view_correction.hpp), and when the rig check sets, keeps, changes and
// drops the rows' correction (rig_check.hpp; the offset's: test_stereo_offset_correction.cpp).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "rig_check.hpp"
#include "view_correction.hpp"
#include "stereo_rig_findings.hpp"
#include "stereo_moved_view.hpp"

namespace nerv::stereo {
namespace {

TEST(stereoViewCorrection, NoPlaneLeavesTheViewAsItIs) {
  ViewCorrection none;
  const cv::Mat right = movedRightView(wallTexture(1), 0);
  EXPECT_TRUE(none.rows().zero());
  EXPECT_EQ(none.columns(), 0.0);
  EXPECT_EQ(none.apply(right).data, right.data);  // the same pixels, not a copy
  none.setRows({0.5, 0, 0});
  EXPECT_NE(none.apply(right).data, right.data);
  none.setRows({});
  EXPECT_EQ(none.apply(right).data, right.data);
}

TEST(stereoViewCorrection, AnOffsetAndATurnAreUndone) {
  const cv::Mat left = wallTexture(2), aligned = movedRightView(left, 0);
  // Against the bilinear resampling's own blur: the aligned view moved by half a row and back.
  ViewCorrection half;
  half.setRows({0.5, 0, 0});
  const double floor = meanViewDifference(half.apply(movedRightView(left, 0.5)), aligned);
  EXPECT_LT(floor, 3.0);
  for (double dy : {1.0, -1.5, 3.0}) {
    const cv::Mat moved = movedRightView(left, dy);
    ViewCorrection fix;
    fix.setRows({dy, 0, 0});
    EXPECT_LT(meanViewDifference(fix.apply(moved), aligned), floor + 0.5) << dy;
    EXPECT_GT(meanViewDifference(moved, aligned), 4 * floor) << dy;
    ViewCorrection wrong;  // the other way doubles it
    wrong.setRows({-dy, 0, 0});
    EXPECT_GT(meanViewDifference(wrong.apply(moved), aligned), 4 * floor) << dy;
  }
  // Turned by 0.3 deg: undone as a rotation, not as rows only.
  const double turn = 0.3 * CV_PI / 180;
  const cv::Mat turned = movedRightView(left, 0, 0.3);
  ViewCorrection rotation, rows_only;
  rotation.setRows({0, std::tan(turn), 0});
  EXPECT_LT(meanViewDifference(rotation.apply(turned), aligned), floor + 0.5);
  EXPECT_GT(meanViewDifference(turned, aligned), 3 * floor);
  // A vertical scale: the rows of the lower half moved down, of the upper half up.
  cv::Mat scaled;
  const cv::Mat stretch = (cv::Mat_<double>(2, 3) << 1, 0, 20, 0, 1.0 / 1.01, 120 - 120 / 1.01);
  cv::warpAffine(left, scaled, stretch, left.size(), cv::INTER_CUBIC | cv::WARP_INVERSE_MAP, cv::BORDER_REFLECT);
  ViewCorrection scale;
  scale.setRows({0, 0, 0.01});
  EXPECT_LT(meanViewDifference(scale.apply(scaled), aligned), floor + 0.5);
}

TEST(stereoViewCorrection, TheOffsetComesOffEveryValidDisparity) {
  ViewCorrection c;
  cv::Mat d = (cv::Mat_<float>(1, 5) << 10.0f, 0.5f, 0.0f, -1.0f, 1.25f);
  const cv::Mat as_matched = d.clone();
  c.correctDisparity(d);  // none set: unchanged
  EXPECT_EQ(cv::norm(d, as_matched, cv::NORM_INF), 0.0);
  c.setColumns(0.75);
  EXPECT_EQ(c.columns(), 0.75);
  const cv::Mat right = wallTexture(9);
  EXPECT_EQ(c.apply(right).data, right.data);  // the offset alone resamples nothing
  c.correctDisparity(d);
  EXPECT_FLOAT_EQ(d.at<float>(0), 9.25f);
  EXPECT_FLOAT_EQ(d.at<float>(1), 0.0f);  // beyond the horizon once corrected: invalid
  EXPECT_FLOAT_EQ(d.at<float>(2), 0.0f);  // invalid stays invalid
  EXPECT_FLOAT_EQ(d.at<float>(3), -1.0f);
  EXPECT_FLOAT_EQ(d.at<float>(4), 0.5f);
  c.setColumns(-1.5);  // read too small: added
  cv::Mat e = as_matched.clone();
  c.correctDisparity(e);
  EXPECT_FLOAT_EQ(e.at<float>(0), 11.5f);
  EXPECT_FLOAT_EQ(e.at<float>(2), 0.0f);
}

TEST(stereoViewCorrection, LargestOverTheView) {
  EXPECT_DOUBLE_EQ((RowPlane{0.5, 0, 0}.largestOver({640, 240})), 0.5);
  EXPECT_DOUBLE_EQ((RowPlane{-0.5, 0.001, -0.002}.largestOver({640, 240})), 0.5 + 0.32 + 0.24);
  EXPECT_TRUE(RowPlane{}.zero());
}

// A rig a row off: the first verdict sets the correction, the next 10 frames are checked on the
// corrected views, and the rig's rows are still an error (it needs a recalibration), but the
// matcher now sees what is left, a few hundredths of a pixel.
TEST(stereoRigCheckCorrection, ARowOffIsCorrectedFromTheNextFrameAndStillAnError) {
  RigCheck rig;
  const cv::Mat left = wallTexture(3), moved = movedRightView(left, 1.0), aligned = movedRightView(left, 0);
  for (int f = 1; f <= 9; ++f) EXPECT_EQ(findingNames(wallFrame(rig, left, moved)), "row_checks") << f;
  const std::vector<RigFinding> tenth = wallFrame(rig, left, moved);
  ASSERT_EQ(findingNames(tenth), "row_checks row_corrections row_misaligned");
  const std::string& first = firstFinding(tenth, RigFinding::Kind::Error)->message;
  EXPECT_NE(first.find("rectification: the right view's rows lie 1.0"), std::string::npos) << first;
  EXPECT_NE(first.find("; from the next frame the stereo_matcher resamples its right views by 1.0"), std::string::npos)
      << first;
  EXPECT_NE(first.find("(row_correction); recalibrate it"), std::string::npos) << first;
  EXPECT_NEAR(rig.rowCorrection().offset_px, 1.0, 0.05);
  EXPECT_NEAR(findingGauge(tenth, "row_correction_px"), 1.0, 0.1);
  EXPECT_NEAR(findingGauge(tenth, "row_residual_px"), 1.0, 0.05);  // measured before the correction
  // The corrected view is the aligned one.
  EXPECT_LT(meanViewDifference(rig.rightToMatch(moved), aligned), 3.0);
  for (int f = 11; f <= 19; ++f) EXPECT_EQ(findingNames(wallFrame(rig, left, moved)), "row_checks") << f;
  const std::vector<RigFinding> twentieth = wallFrame(rig, left, moved);
  ASSERT_EQ(findingNames(twentieth), "row_checks row_misaligned");
  const std::string& second = twentieth[1].message;
  EXPECT_NE(second.find("the right view's rows lie 1.0"), std::string::npos) << second;
  EXPECT_NE(second.find("the stereo_matcher resamples its right views (row_correction), which leaves up to 0.0"),
            std::string::npos)
      << second;
  EXPECT_NEAR(findingGauge(twentieth, "row_offset_px"), 1.0, 0.05);  // the rig against its calibration
  EXPECT_LT(findingGauge(twentieth, "row_residual_px"), 0.1);        // what the matcher sees
  // Back to every tenth frame; the correction stays.
  for (int f = 21; f <= 29; ++f) EXPECT_EQ(findingNames(wallFrame(rig, left, moved)), "") << f;
  EXPECT_NEAR(rig.rowCorrection().offset_px, 1.0, 0.05);
}

TEST(stereoRigCheckCorrection, ATurnIsCorrectedAsATurn) {
  RigCheck rig;
  const cv::Mat left = wallTexture(4), turned = movedRightView(left, 0, 0.2);
  for (int f = 1; f <= 10; ++f) wallFrame(rig, left, turned);
  EXPECT_NEAR(std::atan(rig.rowCorrection().slope_x) * 180 / CV_PI, 0.2, 0.01);
  EXPECT_NEAR(rig.rowCorrection().offset_px, 0.0, 0.1);
  std::vector<RigFinding> twentieth;
  for (int f = 11; f <= 20; ++f) twentieth = wallFrame(rig, left, turned);
  EXPECT_LT(findingGauge(twentieth, "row_residual_px"), 0.1);
  EXPECT_NEAR(findingGauge(twentieth, "row_turn_deg"), 0.2, 0.01);
}

// Within row_correction_above_px (0.25) the views are matched as they come, byte for byte.
TEST(stereoRigCheckCorrection, ASmallOffsetIsLeftAsItIs) {
  RigCheck rig;
  const cv::Mat left = wallTexture(5), right = movedRightView(left, 0.15);
  for (int f = 1; f <= 30; ++f) {
    const std::string s = findingNames(wallFrame(rig, left, right));
    EXPECT_EQ(s.find("row_corrections"), std::string::npos) << f;
  }
  EXPECT_FALSE(rig.rowCorrection().offset_px != 0);
  EXPECT_EQ(rig.rightToMatch(right).data, right.data);
}

// Mended (recalibrated in place, or knocked back): what is left is the correction the other
// way, the checks run on every frame, and the verdict drops the correction.
TEST(stereoRigCheckCorrection, AMendedRigDropsTheCorrection) {
  RigCheck rig;
  const cv::Mat left = wallTexture(6), moved = movedRightView(left, 1.0), aligned = movedRightView(left, 0);
  for (int f = 1; f <= 40; ++f) wallFrame(rig, left, moved);
  ASSERT_NEAR(rig.rowCorrection().offset_px, 1.0, 0.05);
  // Frames 41-49 not checked; 50 reads the corrected view a row off the other way.
  for (int f = 41; f <= 49; ++f) EXPECT_EQ(findingNames(wallFrame(rig, left, aligned)), "") << f;
  EXPECT_EQ(findingNames(wallFrame(rig, left, aligned)), "row_checks log row_rechecks");
  for (int f = 51; f <= 58; ++f) EXPECT_EQ(findingNames(wallFrame(rig, left, aligned)), "row_checks") << f;
  const std::vector<RigFinding> verdict = wallFrame(rig, left, aligned);  // frame 59
  ASSERT_EQ(findingNames(verdict), "row_checks row_corrections log");
  EXPECT_NE(verdict[2].message.find(": aligned; the stereo_matcher no longer resamples its right views"),
            std::string::npos)
      << verdict[2].message;
  EXPECT_TRUE(rig.rowCorrection().zero());
  EXPECT_EQ(rig.rightToMatch(aligned).data, aligned.data);
  EXPECT_EQ(findingGauge(verdict, "row_correction_px"), 0.0);
}

// At most max_row_correction_px anywhere in the view: the rest stays what the matcher sees,
// said as degrading, and the same correction is not set again at every verdict.
TEST(stereoRigCheckCorrection, TheLargestCorrectionIsHeld) {
  RigCheckParams p;
  p.max_row_correction_px = 0.5f;
  RigCheck rig(p);
  const cv::Mat left = wallTexture(7), moved = movedRightView(left, 1.0);
  for (int f = 1; f <= 10; ++f) wallFrame(rig, left, moved);
  EXPECT_NEAR(rig.rowCorrection().offset_px, 0.5, 0.02);
  std::vector<RigFinding> twentieth;
  for (int f = 11; f <= 20; ++f) twentieth = wallFrame(rig, left, moved);
  ASSERT_EQ(findingNames(twentieth), "row_checks row_misaligned");
  EXPECT_NE(twentieth[1].message.find("which leaves up to 0.5"), std::string::npos) << twentieth[1].message;
  EXPECT_NE(twentieth[1].message.find("; disparity and detections degrade, recalibrate it"), std::string::npos)
      << twentieth[1].message;
  for (int f = 21; f <= 29; ++f) EXPECT_EQ(findingNames(wallFrame(rig, left, moved)), "") << f;  // every tenth frame again
}

TEST(stereoRigCheckCorrection, OffLeavesEveryViewAsItIs) {
  RigCheckParams p;
  p.row_correction = false;
  RigCheck rig(p);
  const cv::Mat left = wallTexture(8), moved = movedRightView(left, 1.0);
  std::vector<RigFinding> tenth;
  for (int f = 1; f <= 10; ++f) tenth = wallFrame(rig, left, moved);
  EXPECT_EQ(findingNames(tenth), "row_checks row_misaligned");
  EXPECT_TRUE(rig.rowCorrection().zero());
  EXPECT_EQ(rig.rightToMatch(moved).data, moved.data);
  EXPECT_TRUE(std::isnan(findingGauge(tenth, "row_residual_px")));
}

}  // namespace
}  // namespace nerv::stereo

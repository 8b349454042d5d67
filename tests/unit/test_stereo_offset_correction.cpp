// A right camera turned about its vertical axis since calibration: every disparity a pixel
// larger. The stereo_matcher's offset verdict (rig_check.hpp, disparity_offset.hpp) takes the
// offset it read off every disparity (view_correction.hpp) from the next frame, and says the
// rig still needs a recalibration. Each frame is matched here as the service matches it: the
// right view as the rig check hands it back, the disparity corrected by it.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rig_check.hpp"
#include "stereo_rendered_pair.hpp"
#include "stereo_rig_findings.hpp"

namespace nerv::stereo {
namespace {

using test::Pair;
using test::renderedFrame;

// The median of (a - b) over the pixels valid in both.
double medianDifference(const cv::Mat& a, const cv::Mat& b) {
  std::vector<float> d;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x) {
      const float p = a.at<float>(y, x), q = b.at<float>(y, x);
      if (p > 0 && q > 0) d.push_back(p - q);
    }
  if (d.empty()) return NAN;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

struct Drive {
  RigCheck rig;
  std::string said;
  cv::Mat disparity;  // the last frame's, as matched
  std::unique_ptr<StereoMatcher> matcher = StereoMatcher::create(Params{});
  explicit Drive(const RigCheckParams& p) : rig(p) {}
  std::vector<RigFinding> frame(int k, double shift_px) {
    const Pair& p = renderedFrame(k, 0, shift_px);
    const cv::Mat right = rig.rightToMatch(p.right);
    cv::Mat confidence;
    matcher->compute(p.left, right, disparity, confidence);
    rig.correctDisparity(disparity);
    std::vector<RigFinding> found =
        rig.afterMatching(p.left, right, disparity, {100000LL * k, p.fx, p.cx, p.cy, p.baseline_m});
    for (const RigFinding& f : found)
      if (!f.message.empty()) said += std::to_string(k) + " " + f.name + ": " + f.message + "\n";
    return found;
  }
};

TEST(stereoOffsetCorrection, ACameraTurnedIsCorrectedFromTheFrameAfterTheVerdict) {
  RigCheckParams params;
  params.first_checks = 11;  // ten offsets by frame 11 (frame 1 has no frame before it)
  Drive d(params);
  std::vector<RigFinding> found;
  for (int k = 1; k <= 11; ++k) found = d.frame(k, 1.0);
  // Frame 11: the verdict, the error, and the correction from the next frame.
  ASSERT_NE(findingNames(found).find("offset_corrections disparity_offset"), std::string::npos) << d.said;
  EXPECT_NE(d.said.find("11 disparity_offset: disparity: the disparity reads 0."), std::string::npos) << d.said;
  EXPECT_NE(d.said.find("; from the next frame the stereo_matcher takes 0."), std::string::npos)
      << d.said;
  EXPECT_NE(d.said.find("(offset_correction); distances are corrected to within the check's own bias (about 0.3 px); "
                        "recalibrate the rig"),
            std::string::npos)
      << d.said;
  const double applied = d.rig.offsetCorrection();
  EXPECT_NEAR(applied, 1.0, 0.35);
  EXPECT_NEAR(findingGauge(found, "offset_correction_px"), applied, 1e-6);
  EXPECT_NEAR(findingGauge(found, "disparity_offset_px"), applied, 1e-6);  // the verdict it was set from
  EXPECT_TRUE(d.rig.rowCorrection().zero());  // the rows are in order
  // The next frames are checked each, on the corrected disparity: the verdict at frame 21 is of them.
  d.said.clear();
  for (int k = 12; k <= 21; ++k) {
    found = d.frame(k, 1.0);
    EXPECT_NE(findingNames(found).find("offset_checks"), std::string::npos) << k << "\n" << d.said;
  }
  EXPECT_NE(findingNames(found).find("disparity_offset"), std::string::npos) << d.said;  // still off its calibration
  EXPECT_NE(d.said.find("21 disparity_offset: disparity: the disparity reads "), std::string::npos) << d.said;
  EXPECT_NEAR(findingGauge(found, "disparity_offset_px"), 1.0, 0.35);  // the rig's, against its calibration
  EXPECT_NE(d.said.find("; the stereo_matcher takes "), std::string::npos) << d.said;
  EXPECT_NE(d.said.find("(offset_correction), which leaves "), std::string::npos) << d.said;
  EXPECT_LT(std::abs(findingGauge(found, "disparity_offset_residual_px")), 0.35) << d.said;
  EXPECT_EQ(d.rig.offsetCorrection(), applied);  // unchanged: what is left is within the limit
  // The disparity as matched now lies within the check's error of the unturned camera's, where
  // it lay a pixel off.
  const cv::Mat& unturned = renderedFrame(21, 0, 0).disparity;
  EXPECT_NEAR(medianDifference(renderedFrame(21, 0, 1.0).disparity, unturned), 1.0, 0.1);
  EXPECT_LT(std::abs(medianDifference(d.disparity, unturned)), 0.3);
}

// Not corrected: a rig in order (its reading within the limit), and with the correction off.
TEST(stereoOffsetCorrection, ARigInOrderOrTheCorrectionOffLeavesTheViews) {
  RigCheckParams params;
  params.first_checks = 11;
  Drive in_order(params);
  for (int k = 1; k <= 11; ++k) in_order.frame(k, 0);
  EXPECT_EQ(in_order.rig.offsetCorrection(), 0.0) << in_order.said;
  EXPECT_NE(in_order.said.find(": within the limit"), std::string::npos) << in_order.said;
  const cv::Mat& right = renderedFrame(11, 0, 0).right;
  EXPECT_EQ(in_order.rig.rightToMatch(right).data, right.data);
  params.offset_correction = false;
  Drive off(params);
  for (int k = 1; k <= 11; ++k) off.frame(k, 1.0);
  EXPECT_NE(off.said.find("disparity_offset"), std::string::npos) << off.said;
  EXPECT_EQ(off.rig.offsetCorrection(), 0.0);
  EXPECT_EQ(off.said.find("offset_correction"), std::string::npos) << off.said;
}

}  // namespace
}  // namespace nerv::stereo

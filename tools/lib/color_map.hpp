// Colours of the overlays: one scale for disparity and depth, and one colour
// per detection verdict and normal class, so every panel and the report agree.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::viz {

// BGR colours (OpenCV order).
const cv::Scalar kKeptColor(0, 220, 0);          // kept detection
const cv::Scalar kRemovedColor(0, 0, 255);       // removed hypothesis
const cv::Scalar kLabelColor(255, 200, 0);       // ground-truth box
const cv::Scalar kDontCareColor(160, 160, 160);  // ground-truth DontCare region
const cv::Scalar kGroundColor(0, 140, 255);      // ground normal / ground model (orange)
const cv::Scalar kObjectColor(0, 220, 0);        // object (upright) normal
const cv::Scalar kErrorColor(255, 0, 255);       // error-like normal
const cv::Scalar kOtherColor(150, 150, 150);     // normal of no class
const cv::Scalar kHorizonColor(0, 255, 255);     // horizon row

// Turbo colour of t in [0, 1] (0 = blue, 1 = dark red); t is clamped.
cv::Vec3b turbo(float t);

// CV_32F disparity (<= 0 or non-finite invalid) -> BGR; invalid pixels black,
// d in [0, max_disparity] mapped onto turbo (near = red).
cv::Mat colorizeDisparity(const cv::Mat& disparity, float max_disparity);

// Depth colour: near_m -> red ... far_m -> blue, on a log scale so near
// obstacles are told apart.
cv::Vec3b depthColor(float depth_m, float near_m = 3.0f, float far_m = 60.0f);

// A horizontal colour bar with min/max labels drawn into `panel` at `box`.
void drawColorBar(cv::Mat& panel, const cv::Rect& box, bool depth, float lo, float hi,
                  const char* unit);

}  // namespace nerv::viz

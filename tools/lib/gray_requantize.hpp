// Gray images as valid as the decoder's own: the luma of a color image,
// 0.299 R + 0.587 G + 0.114 B, quantized as floor(luma + offset). Offset 0.5
// rounds (cv::cvtColor's choice); other offsets move the level boundaries, so
// any two results lie within one gray level of each other and carry the same
// information. Matching on several of them shows how much of a detection
// figure is the quantization's noise rather than the method
// (docs/detection_quality.md "The noise band of a figure").
#pragma once

#include <opencv2/core.hpp>

namespace nerv {

// bgr: CV_8UC3 (channel order B, G, R as cv::imread gives it); offset in
// [0, 1). Returns CV_8UC1 of the same size. Throws std::invalid_argument for
// another type or an offset outside [0, 1).
cv::Mat requantizedGray(const cv::Mat& bgr, double offset);

}  // namespace nerv

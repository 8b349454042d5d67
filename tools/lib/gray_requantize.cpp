#include "gray_requantize.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nerv {

cv::Mat requantizedGray(const cv::Mat& bgr, double offset) {
  if (bgr.type() != CV_8UC3)
    throw std::invalid_argument("requantizedGray wants an 8-bit color image, got " + std::to_string(bgr.channels()) +
                                " channel(s) of depth " + std::to_string(bgr.depth()));
  if (!(offset >= 0 && offset < 1))
    throw std::invalid_argument("requantizedGray wants an offset in [0, 1), got " + std::to_string(offset));
  cv::Mat gray(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y) {
    const cv::Vec3b* in = bgr.ptr<cv::Vec3b>(y);
    uint8_t* out = gray.ptr<uint8_t>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      const double luma = 0.299 * in[x][2] + 0.587 * in[x][1] + 0.114 * in[x][0];
      out[x] = static_cast<uint8_t>(std::min(255.0, std::floor(luma + offset)));
    }
  }
  return gray;
}

}  // namespace nerv

#include "frozen_view.hpp"

#include <cstring>

namespace nerv::stereo {

uint64_t imageDigest(const cv::Mat& image) {
  uint64_t h = 1469598103934665603ull;
  const size_t row_bytes = image.cols * image.elemSize();
  for (int y = 0; y < image.rows; ++y) {
    const uchar* p = image.ptr<uchar>(y);
    size_t i = 0;
    for (; i + 8 <= row_bytes; i += 8) {
      uint64_t word;
      std::memcpy(&word, p + i, 8);
      h = (h ^ word) * 1099511628211ull;
    }
    for (; i < row_bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  // The size is part of what the image is.
  h = (h ^ static_cast<uint64_t>(image.cols)) * 1099511628211ull;
  return (h ^ static_cast<uint64_t>(image.rows)) * 1099511628211ull;
}

std::string FrozenViewCheck::push(const cv::Mat& left, const cv::Mat& right) {
  const uint64_t l = imageDigest(left), r = imageDigest(right);
  std::string stopped;
  if (have_previous_) {
    const bool left_same = l == left_, right_same = r == right_;
    if (left_same != right_same) stopped = left_same ? "left" : "right";
  }
  have_previous_ = true;
  left_ = l, right_ = r;
  if (stopped.empty()) {
    run_ = 0;
    stopped_.clear();
    return "";
  }
  run_ = stopped == stopped_ ? run_ + 1 : 1;
  stopped_ = stopped;
  return run_ >= min_frames_ ? stopped : "";
}

}  // namespace nerv::stereo

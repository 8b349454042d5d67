// Shared reference of the stereo tests: nerv_sgm's last step written out per
// pixel. The 3x3 median (replicated border, invalid = 0 counted as a value)
// replaces a valid pixel; an invalid pixel inside the image takes it when at
// least 6 of its 8 neighbours are valid, with the lowest of their
// confidences (at least 1e-3).
#pragma once

#include <opencv2/core.hpp>

#include <algorithm>
#include <vector>

namespace nerv::stereo {

inline void referenceMedianFill(const cv::Mat& d, const cv::Mat& c, cv::Mat& out_d, cv::Mat& out_c) {
  out_d = d.clone();
  out_c = c.clone();
  auto clampY = [&](int y) { return std::clamp(y, 0, d.rows - 1); };
  auto clampX = [&](int x) { return std::clamp(x, 0, d.cols - 1); };
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) {
      std::vector<float> w;
      int valid = 0;
      float lowest = 1.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const float v = d.at<float>(clampY(y + dy), clampX(x + dx));
          w.push_back(v);
          if ((dy || dx) && v > 0) {
            ++valid;
            lowest = std::min(lowest, c.at<float>(clampY(y + dy), clampX(x + dx)));
          }
        }
      std::nth_element(w.begin(), w.begin() + 4, w.end());
      const float m = w[4];
      if (!(m > 0)) continue;
      const bool inner = y > 0 && x > 0 && y + 1 < d.rows && x + 1 < d.cols;
      if (d.at<float>(y, x) > 0) {
        out_d.at<float>(y, x) = m;
      } else if (inner && valid >= 6) {
        out_d.at<float>(y, x) = m;
        out_c.at<float>(y, x) = std::max(lowest, 1e-3f);
      }
    }
}

// The disparity alone.
inline cv::Mat referenceMedianFill(const cv::Mat& d) {
  cv::Mat out_d, out_c;
  referenceMedianFill(d, cv::Mat(d.size(), CV_32F, cv::Scalar(1.0f)), out_d, out_c);
  return out_d;
}

}  // namespace nerv::stereo

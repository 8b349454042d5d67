#include "v_disparity.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::stixel {

VDisparity computeVDisparity(const cv::Mat& disparity, float max_disparity_px,
                             int column_step) {
  column_step = std::max(1, column_step);
  CV_Assert(disparity.type() == CV_32F);
  VDisparity vd;
  vd.rows = disparity.rows;
  vd.bins = std::max(1, static_cast<int>(std::ceil(max_disparity_px)));
  vd.count.assign(static_cast<size_t>(vd.rows) * vd.bins, 0);
  vd.sum_d.assign(static_cast<size_t>(vd.rows) * vd.bins, 0.0f);
  int valid = 0;
  // Four rows at a time, interleaved per column: neighbouring road pixels of one
  // row fall into the same cell, and a single row's increments would form one
  // long store-to-load dependency chain; four rows give four independent ones.
  constexpr int kRows = 4;
  for (int v0 = 0; v0 < disparity.rows; v0 += kRows) {
    const int nr = std::min(kRows, disparity.rows - v0);
    const float* row[kRows];
    int* cnt[kRows];
    float* sum[kRows];
    for (int r = 0; r < kRows; ++r) {
      const int v = v0 + std::min(r, nr - 1);
      row[r] = disparity.ptr<float>(v);
      cnt[r] = &vd.count[static_cast<size_t>(v) * vd.bins];
      sum[r] = &vd.sum_d[static_cast<size_t>(v) * vd.bins];
    }
    for (int u = 0; u < disparity.cols; u += column_step) {
      for (int r = 0; r < nr; ++r) {
        const float d = row[r][u];
        if (!validDisparity(d, max_disparity_px)) continue;
        const int k = static_cast<int>(d);
        ++cnt[r][k];
        sum[r][k] += d;
        ++valid;
      }
    }
  }
  vd.valid_pixels = valid;
  vd.sampled_columns = (disparity.cols + column_step - 1) / column_step;
  return vd;
}

}  // namespace nerv::stixel

#include "v_disparity.hpp"

#include <cmath>

namespace nerv::stixel {

VDisparity computeVDisparity(const cv::Mat& disparity, float max_disparity_px) {
  CV_Assert(disparity.type() == CV_32F);
  VDisparity vd;
  vd.rows = disparity.rows;
  vd.bins = std::max(1, static_cast<int>(std::ceil(max_disparity_px)));
  vd.count.assign(static_cast<size_t>(vd.rows) * vd.bins, 0);
  vd.sum_d.assign(static_cast<size_t>(vd.rows) * vd.bins, 0.0f);
  int valid = 0;
  for (int v = 0; v < disparity.rows; ++v) {
    const float* row = disparity.ptr<float>(v);
    int* cnt = &vd.count[static_cast<size_t>(v) * vd.bins];
    float* sum = &vd.sum_d[static_cast<size_t>(v) * vd.bins];
    for (int u = 0; u < disparity.cols; ++u) {
      const float d = row[u];
      if (!validDisparity(d, max_disparity_px)) continue;
      const int k = static_cast<int>(d);
      ++cnt[k];
      sum[k] += d;
      ++valid;
    }
  }
  vd.valid_pixels = valid;
  return vd;
}

}  // namespace nerv::stixel

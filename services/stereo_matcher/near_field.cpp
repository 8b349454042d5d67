#include "near_field.hpp"

#include <algorithm>

namespace nerv::stereo {

int fuseNearField(cv::Mat& full_disparity, cv::Mat& full_confidence, const cv::Mat& near_disparity,
                  const cv::Mat& near_confidence, const NearFieldParams& p) {
  CV_Assert(full_disparity.type() == CV_32FC1 && near_disparity.type() == CV_32FC1);
  CV_Assert(full_confidence.size() == full_disparity.size() && near_confidence.size() == near_disparity.size());
  const int s = p.scale;
  const float beyond = p.reach_px + p.margin_px;
  const float beyond_near = beyond / static_cast<float>(s);
  int replaced = 0;
  int checked_row = -1;
  bool row_has_near = false;
  for (int y = 0; y < full_disparity.rows; ++y) {
    const int ny = std::min(y / s, near_disparity.rows - 1);
    const float* nd = near_disparity.ptr<float>(ny);
    if (ny != checked_row) {  // most rows of most frames see nothing that near: skip them
      checked_row = ny;
      row_has_near = std::any_of(nd, nd + near_disparity.cols, [&](float v) { return v >= beyond_near; });
    }
    if (!row_has_near) continue;
    const float* nc = near_confidence.ptr<float>(ny);
    float* d = full_disparity.ptr<float>(y);
    float* c = full_confidence.ptr<float>(y);
    for (int x = 0; x < full_disparity.cols; ++x) {
      const int nx = std::min(x / s, near_disparity.cols - 1);
      const float near = nd[nx] * static_cast<float>(s);
      if (!(near >= beyond)) continue;  // no near-field surface beyond the reach (or invalid)
      d[x] = near;
      c[x] = nc[nx];
      ++replaced;
    }
  }
  return replaced;
}

}  // namespace nerv::stereo

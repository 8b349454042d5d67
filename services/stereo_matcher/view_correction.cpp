#include "view_correction.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace nerv::stereo {

void ViewCorrection::setRows(const RowPlane& plane) {
  plane_ = plane;
  size_ = cv::Size();  // the maps are built anew on the next view
}

void ViewCorrection::setColumns(double offset_px) { columns_px_ = offset_px; }

void ViewCorrection::correctDisparity(cv::Mat& disparity) const {
  if (columns_px_ == 0 || disparity.type() != CV_32FC1) return;
  const float e = static_cast<float>(columns_px_);
  for (int y = 0; y < disparity.rows; ++y) {
    float* d = disparity.ptr<float>(y);
    // A point whose disparity was all offset lies beyond the horizon: unmeasured, as the matcher says it.
    for (int x = 0; x < disparity.cols; ++x) d[x] = d[x] > 0 ? std::max(d[x] - e, 0.0f) : d[x];
  }
}

const cv::Mat& ViewCorrection::apply(const cv::Mat& right) {
  if (plane_.zero()) return right;
  if (right.size() != size_) {
    size_ = right.size();
    cv::Mat map(size_, CV_32FC2);
    const double cx = 0.5 * size_.width, cy = 0.5 * size_.height;
    for (int y = 0; y < size_.height; ++y) {
      auto* row = map.ptr<cv::Vec2f>(y);
      const double v = y - cy;
      for (int x = 0; x < size_.width; ++x) {
        const double u = x - cx;
        row[x] = cv::Vec2f(static_cast<float>(x - plane_.slope_x * v),
                           static_cast<float>(y + plane_.offset_px + plane_.slope_x * u + plane_.slope_y * v));
      }
    }
    // Fixed-point maps (1/32 px): remap's fast path.
    cv::convertMaps(map, cv::noArray(), map_xy_, map_frac_, CV_16SC2);
  }
  cv::remap(right, out_, map_xy_, map_frac_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out_;
}

}  // namespace nerv::stereo

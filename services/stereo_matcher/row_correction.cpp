#include "row_correction.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace nerv::stereo {

void RowCorrection::set(const RowPlane& plane) {
  plane_ = plane;
  size_ = cv::Size();  // the maps are built anew on the next view
}

const cv::Mat& RowCorrection::apply(const cv::Mat& right) {
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

#include "local_normals.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::snv {
namespace {

int firstGrid(int from, int interval) { return (from + interval - 1) / interval * interval; }

// How far the windows of a pixel reach: 2 * max_radius_px from the centre, plus the
// integral image's row/column before them.
int windowMargin(int max_radius_px) { return 2 * max_radius_px + 1; }

}  // namespace

int localNormalsInRect(const IntegralNormalField& field, const cv::Rect& rect, int interval_px,
                       std::vector<LocalNormal>& out) {
  CV_Assert(interval_px >= 1);
  if (field.empty() || rect.width <= 0 || rect.height <= 0) return 0;
  // Samples live in the prepared region (the caller sizes it with rowBandFor()
  // or regionFor()).
  const int u0 = firstGrid(std::max(rect.x, field.colBegin()), interval_px);
  const int v0 = firstGrid(std::max(rect.y, field.rowBegin()), interval_px);
  const int u1 = std::min(rect.x + rect.width, field.colEnd());
  const int v1 = std::min(rect.y + rect.height, field.rowEnd());
  if (u0 >= u1 || v0 >= v1) return 0;
  const int count = (u1 - u0 + interval_px - 1) / interval_px;
  int samples = 0;
  NormalRow row;
  for (int v = v0; v < v1; v += interval_px) {
    samples += count;
    field.normalRow(v, u0, count, interval_px, row);
    for (int i = 0; i < count; ++i)
      if (row.radius[i] >= 1 && !std::isnan(row.nx[i]))
        out.push_back({u0 + i * interval_px, v, cv::Vec3f(row.nx[i], row.ny[i], row.nz[i])});
  }
  return samples;
}

cv::Rect regionFor(const cv::Rect& rect, const cv::Size& image, int max_radius_px) {
  if (rect.width <= 0 || rect.height <= 0) return cv::Rect();
  const int margin = windowMargin(max_radius_px);
  return cv::Rect(rect.x - margin, rect.y - margin, rect.width + 2 * margin, rect.height + 2 * margin) &
         cv::Rect(0, 0, image.width, image.height);
}

cv::Range rowBandFor(const std::vector<cv::Rect>& rects, int image_rows, int max_radius_px) {
  int lo = image_rows, hi = 0;
  for (const cv::Rect& r : rects) {
    if (r.width <= 0 || r.height <= 0) continue;
    lo = std::min(lo, r.y);
    hi = std::max(hi, r.y + r.height);
  }
  if (lo >= hi) return cv::Range(0, 0);
  const int margin = windowMargin(max_radius_px);
  return cv::Range(std::clamp(lo - margin, 0, image_rows), std::clamp(hi + margin, 0, image_rows));
}

}  // namespace nerv::snv

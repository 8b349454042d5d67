#include "color_map.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nerv::viz {

cv::Vec3b turbo(float t) {
  static const cv::Mat lut = [] {
    cv::Mat ramp(1, 256, CV_8U);
    for (int i = 0; i < 256; ++i) ramp.at<uint8_t>(i) = static_cast<uint8_t>(i);
    cv::Mat colored;
    cv::applyColorMap(ramp, colored, cv::COLORMAP_TURBO);
    return colored;
  }();
  if (!std::isfinite(t)) t = 0;
  const int i = std::clamp(static_cast<int>(std::lround(t * 255.0f)), 0, 255);
  return lut.at<cv::Vec3b>(0, i);
}

cv::Mat colorizeDisparity(const cv::Mat& disparity, float max_disparity) {
  cv::Mat out(disparity.size(), CV_8UC3, cv::Scalar::all(0));
  const float scale = max_disparity > 0 ? 1.0f / max_disparity : 0.0f;
  for (int v = 0; v < disparity.rows; ++v) {
    const float* d = disparity.ptr<float>(v);
    cv::Vec3b* o = out.ptr<cv::Vec3b>(v);
    for (int u = 0; u < disparity.cols; ++u)
      if (d[u] > 0 && std::isfinite(d[u])) o[u] = turbo(d[u] * scale);
  }
  return out;
}

cv::Vec3b depthColor(float depth_m, float near_m, float far_m) {
  if (!(depth_m > 0)) return {128, 128, 128};
  const float t = std::log(std::max(depth_m, near_m) / near_m) / std::log(far_m / near_m);
  return turbo(1.0f - std::clamp(t, 0.0f, 1.0f));
}

void drawColorBar(cv::Mat& panel, const cv::Rect& box, bool depth, float lo, float hi,
                  const char* unit) {
  const cv::Rect inside = box & cv::Rect(0, 0, panel.cols, panel.rows);
  if (inside.width < 4 || inside.height < 2) return;
  for (int x = 0; x < box.width; ++x) {
    const float value = lo + (hi - lo) * x / std::max(1, box.width - 1);
    const cv::Vec3b c = depth ? depthColor(value, lo, hi) : turbo(hi > 0 ? value / hi : 0);
    cv::line(panel, {box.x + x, box.y}, {box.x + x, box.y + box.height - 1}, cv::Scalar(c[0], c[1], c[2]));
  }
  cv::rectangle(panel, box, cv::Scalar::all(255), 1);
  char text[64];
  std::snprintf(text, sizeof text, "%g %s", lo, unit);
  cv::putText(panel, text, {box.x, box.y - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar::all(255), 1,
              cv::LINE_AA);
  std::snprintf(text, sizeof text, "%g %s", hi, unit);
  int base = 0;
  const cv::Size s = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &base);
  cv::putText(panel, text, {box.x + box.width - s.width, box.y - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
              cv::Scalar::all(255), 1, cv::LINE_AA);
}

}  // namespace nerv::viz

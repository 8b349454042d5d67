#include "motion_tracks.hpp"

#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include "percentile.hpp"

namespace nerv::stereo {

MotionTracks trackMotion(const cv::Mat& previous_left, const cv::Mat& left, const cv::Mat& disparity,
                         const MotionTrackParams& p) {
  MotionTracks out;
  if (left.empty() || left.type() != CV_8UC1 || previous_left.type() != CV_8UC1 ||
      previous_left.size() != left.size() || disparity.size() != left.size() || disparity.type() != CV_32FC1)
    return out;
  out.matched = matchedTexturedPoints(left, disparity, {p.grid_px, p.window_px, p.max_points});
  if (out.matched.left.empty()) return out;
  const int r = std::max(1, p.window_px / 2);
  out.before = out.matched.left;
  std::vector<float> error;
  // Between frames the rows near the image bottom move by tens of pixels: 4 levels.
  cv::calcOpticalFlowPyrLK(left, previous_left, out.matched.left, out.before, out.tracked, error,
                           cv::Size(2 * r + 1, 2 * r + 1), 3,
                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01));
  for (size_t i = 0; i < out.tracked.size(); ++i)
    if (error[i] > p.max_track_error || !std::isfinite(out.before[i].x) || !std::isfinite(out.before[i].y))
      out.tracked[i] = 0;
  return out;
}

float stepAtPoints(double k, std::vector<double> magnitudes) {
  return static_cast<float>(std::abs(k) * percentile(std::move(magnitudes), 0.9));
}

}  // namespace nerv::stereo

#include "shutter_sync.hpp"

#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "robust_fit.hpp"

namespace nerv::stereo {

ShutterSync measureShutterSync(const MotionTracks& tracks, const cv::Mat& left, const cv::Mat& right, double fx,
                               double cx, double cy, const ShutterSyncParams& p) {
  ShutterSync out;
  const MatchedPoints& m = tracks.matched;
  if (left.empty() || left.type() != CV_8UC1 || right.type() != CV_8UC1 || right.size() != left.size() ||
      !(fx > 0) || !std::isfinite(cx) || !std::isfinite(cy) || static_cast<int>(m.left.size()) < p.min_points ||
      tracks.before.size() != m.left.size() || tracks.tracked.size() != m.left.size())
    return out;
  const int r = std::max(1, p.tracking.window_px / 2);
  std::vector<cv::Point2f> in_right = m.right;
  std::vector<uchar> ok;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(left, right, m.left, in_right, ok, error, cv::Size(2 * r + 1, 2 * r + 1), 2,
                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01),
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<FitRow<5>> x_stereo;
  std::vector<FitRow<6>> x_motion;
  std::vector<double> y_stereo, y_motion, vd;
  for (size_t i = 0; i < m.left.size(); ++i) {
    if (!ok[i] || !tracks.tracked[i] || error[i] > p.tracking.max_track_error || !std::isfinite(in_right[i].y))
      continue;
    if (std::abs(in_right[i].x - m.right[i].x) > p.max_horizontal_miss_px) continue;
    const double u = m.left[i].x - cx, v = m.left[i].y - cy, d = m.disparity[i];
    // The previous view's coordinates: there v - v_before = kappa v_before (d - offset) holds exactly.
    const double ub = tracks.before[i].x - cx, vb = tracks.before[i].y - cy;
    x_stereo.push_back({1.0, u, v, d, v * d});
    y_stereo.push_back(in_right[i].y - m.left[i].y);
    x_motion.push_back(stepFlowRow(vb, ub, d, fx));
    y_motion.push_back(m.left[i].y - tracks.before[i].y);
    vd.push_back(std::abs(vb * d));
  }
  out.points = static_cast<int>(y_stereo.size());
  if (out.points < p.min_points) return out;
  FitRow<5> stereo;
  FitRow<6> motion;
  if (!huberFit<5>(x_stereo, y_stereo, stereo) || !huberFit<6>(x_motion, y_motion, motion)) return out;
  out.k_stereo = stereo[4];
  out.k_motion = motion[4];
  out.motion_px = stepAtPoints(out.k_motion, std::move(vd));
  out.moving = out.k_motion > 0 && out.motion_px >= p.min_motion_px;
  if (!out.moving) return out;
  out.offset = static_cast<float>(out.k_stereo / out.k_motion);
  out.valid = std::isfinite(out.offset);
  return out;
}

ShutterSync measureShutterSync(const cv::Mat& previous_left, const cv::Mat& left, const cv::Mat& right,
                               const cv::Mat& disparity, double fx, double cx, double cy,
                               const ShutterSyncParams& p) {
  if (right.empty() || right.size() != left.size()) return {};
  return measureShutterSync(trackMotion(previous_left, left, disparity, p.tracking), left, right, fx, cx, cy, p);
}

std::string describeViewDelay(const MedianVerdict& delays) {
  const float m = delays.median();
  char line[200];
  std::snprintf(line, sizeof line,
                "the right view is taken %.1f ms %s the left (median of the last %d checks while moving, %.1f to %.1f ms)",
                std::abs(m), m >= 0 ? "after" : "before", delays.samples(), delays.lowest(), delays.highest());
  return line;
}

}  // namespace nerv::stereo

#include "view_order_check.hpp"

#include <opencv2/video/tracking.hpp>

#include <cmath>
#include <vector>

#include "textured_points.hpp"

namespace nerv::stereo {

ViewOrder measureViewOrder(const cv::Mat& left, const cv::Mat& right, const ViewOrderParams& p) {
  ViewOrder out;
  if (left.empty() || left.type() != CV_8UC1 || right.size() != left.size() || right.type() != CV_8UC1) return out;
  const std::vector<cv::Point2f> from = texturedPoints(left, {p.grid_px, p.window_px, p.max_points});
  if (static_cast<int>(from.size()) < p.min_votes) return out;
  const cv::Size window(p.window_px | 1, p.window_px | 1);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
  std::vector<cv::Point2f> to, back;
  std::vector<uchar> status, status_back;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(left, right, from, to, status, error, window, p.pyramid_levels, stop);
  cv::calcOpticalFlowPyrLK(right, left, to, back, status_back, error, window, p.pyramid_levels, stop);
  int rightward = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    if (!status[i] || !status_back[i]) continue;
    const cv::Point2f move = to[i] - from[i];
    if (!std::isfinite(move.x) || !std::isfinite(move.y) || cv::norm(back[i] - from[i]) > p.max_return_px ||
        std::abs(move.y) > p.max_row_drift_px || std::abs(move.x) < p.min_sideways_px)
      continue;
    ++out.votes;
    if (move.x > 0) ++rightward;
  }
  if (out.votes < p.min_votes) return out;
  out.valid = true;
  out.share_rightward = static_cast<float>(rightward) / static_cast<float>(out.votes);
  out.swapped = out.share_rightward >= p.swapped_share;
  return out;
}

}  // namespace nerv::stereo

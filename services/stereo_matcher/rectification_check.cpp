#include "rectification_check.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace nerv::stereo {

namespace {

float medianOf(std::vector<float> v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  const float upper = v[mid];
  if (v.size() % 2) return upper;
  return 0.5f * (upper + *std::max_element(v.begin(), v.begin() + static_cast<long>(mid)));
}

}  // namespace

RowOffset measureRowOffset(const cv::Mat& left, const cv::Mat& right, const cv::Mat& disparity,
                           const RowOffsetParams& p) {
  RowOffset out;
  if (left.empty() || left.type() != CV_8UC1 || right.size() != left.size() || right.type() != CV_8UC1 ||
      disparity.size() != left.size() || disparity.type() != CV_32FC1)
    return out;
  // Grid points away from the border, where the window lies inside both views.
  const int r = std::max(1, p.window_px / 2);
  const int margin = r + 2;
  if (left.cols <= 2 * margin || left.rows <= 2 * margin) return out;
  struct Candidate {
    float score;
    cv::Point2f at;
    float d;
  };
  std::vector<Candidate> candidates;
  const int step = std::max(2, p.grid_px);
  for (int y = margin; y < left.rows - margin; y += step) {
    const float* drow = disparity.ptr<float>(y);
    for (int x = margin; x < left.cols - margin; x += step) {
      const float d = drow[x];
      if (!(d > 0) || x - d < margin) continue;
      // Structure tensor of central differences over the window; its smaller eigenvalue.
      double sxx = 0, syy = 0, sxy = 0;
      for (int v = y - r; v <= y + r; ++v) {
        const uchar* up = left.ptr<uchar>(v - 1);
        const uchar* row = left.ptr<uchar>(v);
        const uchar* down = left.ptr<uchar>(v + 1);
        for (int u = x - r; u <= x + r; ++u) {
          const int gx = row[u + 1] - row[u - 1], gy = down[u] - up[u];
          sxx += gx * gx, syy += gy * gy, sxy += gx * gy;
        }
      }
      const double half_trace = 0.5 * (sxx + syy), half_diff = 0.5 * (sxx - syy);
      const double min_eig = half_trace - std::sqrt(half_diff * half_diff + sxy * sxy);
      if (min_eig > 0) candidates.push_back({static_cast<float>(min_eig), cv::Point2f(x, y), d});
    }
  }
  if (static_cast<int>(candidates.size()) > p.max_points) {
    std::nth_element(candidates.begin(), candidates.begin() + p.max_points, candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    candidates.resize(static_cast<size_t>(p.max_points));
  }
  std::vector<cv::Point2f> from, to;
  std::vector<float> disp;
  for (const Candidate& c : candidates) {
    from.push_back(c.at);
    to.push_back({c.at.x - c.d, c.at.y});
    disp.push_back(c.d);
  }
  if (static_cast<int>(from.size()) < p.min_points) {
    out.points = static_cast<int>(from.size());
    return out;
  }
  std::vector<uchar> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(left, right, from, to, status, error, cv::Size(2 * r + 1, 2 * r + 1), 2,
                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01),
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<float> dy;
  dy.reserve(from.size());
  for (size_t i = 0; i < from.size(); ++i) {
    if (!status[i] || !std::isfinite(to[i].x) || !std::isfinite(to[i].y)) continue;
    if (std::abs(to[i].x - (from[i].x - disp[i])) > p.max_horizontal_miss_px) continue;
    dy.push_back(to[i].y - from[i].y);
  }
  out.points = static_cast<int>(dy.size());
  if (out.points < p.min_points) return out;
  out.offset_px = medianOf(dy);
  std::vector<float> dev(dy.size());
  for (size_t i = 0; i < dy.size(); ++i) dev[i] = std::abs(dy[i] - out.offset_px);
  out.spread_px = 1.4826f * medianOf(dev);
  out.valid = true;
  return out;
}

bool RowOffsetMonitor::add(const RowOffset& m) {
  if (!m.valid) return false;
  offsets_.push_back(m.offset_px);
  points_.push_back(m.points);
  while (static_cast<int>(offsets_.size()) > window_) offsets_.pop_front(), points_.pop_front();
  if (++since_verdict_ < window_) return false;
  since_verdict_ = 0;
  return true;
}

float RowOffsetMonitor::median() const { return medianOf({offsets_.begin(), offsets_.end()}); }

std::string RowOffsetMonitor::describe() const {
  const float m = median();
  const int lo = points_.empty() ? 0 : *std::min_element(points_.begin(), points_.end());
  const int hi = points_.empty() ? 0 : *std::max_element(points_.begin(), points_.end());
  char line[200];
  std::snprintf(line, sizeof line, "the right view's rows lie %.2f px %s the left's (median of the last %d checks, %d-%d points each)",
                std::abs(m), m >= 0 ? "below" : "above", samples(), lo, hi);
  return line;
}

}  // namespace nerv::stereo

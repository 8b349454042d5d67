#include "shutter_sync.hpp"

#include "textured_points.hpp"

#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace nerv::stereo {

namespace {

constexpr int kTerms = 5;
using Row = std::array<double, kTerms>;

double medianOf(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  return v[mid];
}

// Least squares of y on the rows of x, reweighted with Huber's weights (k = 1.345 robust
// sigmas, the scale from the residuals' median absolute deviation), from a zero start.
// Returns false when the terms cannot be separated at these points.
bool robustFit(const std::vector<Row>& x, const std::vector<double>& y, Row& coef) {
  coef.fill(0);
  std::vector<double> res(y.size());
  for (int iter = 0; iter < 10; ++iter) {
    for (size_t i = 0; i < y.size(); ++i) {
      double m = 0;
      for (int j = 0; j < kTerms; ++j) m += coef[j] * x[i][j];
      res[i] = y[i] - m;
    }
    std::vector<double> abs_res(res.size());
    for (size_t i = 0; i < res.size(); ++i) abs_res[i] = std::abs(res[i]);
    const double scale = std::max(1e-3, 1.4826 * medianOf(abs_res));
    cv::Matx<double, kTerms, kTerms> ata = cv::Matx<double, kTerms, kTerms>::zeros();
    cv::Vec<double, kTerms> atb = cv::Vec<double, kTerms>::all(0);
    for (size_t i = 0; i < y.size(); ++i) {
      const double r = std::abs(res[i]) / scale, w = iter == 0 || r <= 1.345 ? 1.0 : 1.345 / r;
      for (int j = 0; j < kTerms; ++j) {
        atb[j] += w * x[i][j] * y[i];
        for (int k = 0; k < kTerms; ++k) ata(j, k) += w * x[i][j] * x[i][k];
      }
    }
    cv::Vec<double, kTerms> sol;
    if (!cv::solve(ata, atb, sol, cv::DECOMP_CHOLESKY)) return false;
    for (int j = 0; j < kTerms; ++j) coef[j] = sol[j];
  }
  for (double c : coef)
    if (!std::isfinite(c)) return false;
  return true;
}

bool gray(const cv::Mat& m, const cv::Size& size) { return !m.empty() && m.type() == CV_8UC1 && m.size() == size; }

}  // namespace

ShutterSync measureShutterSync(const cv::Mat& previous_left, const cv::Mat& left, const cv::Mat& right,
                               const cv::Mat& disparity, double fx, double cx, double cy,
                               const ShutterSyncParams& p) {
  ShutterSync out;
  if (!gray(left, left.size()) || !gray(right, left.size()) || !gray(previous_left, left.size()) ||
      disparity.size() != left.size() || disparity.type() != CV_32FC1 || !(fx > 0) || !std::isfinite(cx) ||
      !std::isfinite(cy))
    return out;
  const int r = std::max(1, p.window_px / 2);
  MatchedPoints matched = matchedTexturedPoints(left, disparity, {p.grid_px, p.window_px, p.max_points});
  if (static_cast<int>(matched.left.size()) < p.min_points) return out;
  const std::vector<cv::Point2f>& points = matched.left;
  std::vector<cv::Point2f> in_previous = points;
  const cv::Size window(2 * r + 1, 2 * r + 1);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01);
  std::vector<uchar> ok_right, ok_previous;
  std::vector<float> err_right, err_previous;
  cv::calcOpticalFlowPyrLK(left, right, points, matched.right, ok_right, err_right, window, 2, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  // Between frames the rows near the image bottom move by tens of pixels: one more level.
  cv::calcOpticalFlowPyrLK(left, previous_left, points, in_previous, ok_previous, err_previous, window, 3, stop);

  std::vector<Row> x_stereo, x_motion;
  std::vector<double> y_stereo, y_motion, vd;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!ok_right[i] || !ok_previous[i] || err_right[i] > p.max_track_error || err_previous[i] > p.max_track_error)
      continue;
    if (!std::isfinite(matched.right[i].y) || !std::isfinite(in_previous[i].y)) continue;
    if (std::abs(matched.right[i].x - (points[i].x - matched.disparity[i])) > p.max_horizontal_miss_px) continue;
    const double u = points[i].x - cx, v = points[i].y - cy, d = matched.disparity[i];
    x_stereo.push_back({1.0, u, v, d, v * d});
    x_motion.push_back({fx + v * v / fx, u * v / fx, u, d, v * d});
    y_stereo.push_back(matched.right[i].y - points[i].y);
    y_motion.push_back(in_previous[i].y - points[i].y);
    vd.push_back(std::abs(v * d));
  }
  out.points = static_cast<int>(y_stereo.size());
  if (out.points < p.min_points) return out;
  Row stereo, motion;
  if (!robustFit(x_stereo, y_stereo, stereo) || !robustFit(x_motion, y_motion, motion)) return out;
  out.k_stereo = stereo[4];
  out.k_motion = motion[4];
  const size_t p90 = std::min(vd.size() - 1, static_cast<size_t>(0.9 * static_cast<double>(vd.size() - 1) + 0.5));
  std::nth_element(vd.begin(), vd.begin() + static_cast<long>(p90), vd.end());
  out.motion_px = static_cast<float>(std::abs(out.k_motion) * vd[p90]);
  out.moving = out.k_motion < 0 && out.motion_px >= p.min_motion_px;
  if (!out.moving) return out;
  out.offset = static_cast<float>(-out.k_stereo / out.k_motion);
  out.valid = std::isfinite(out.offset);
  return out;
}

bool ViewDelayMonitor::add(float delay_ms) { return std::isfinite(delay_ms) && delays_.add(delay_ms); }

float ViewDelayMonitor::median() const {
  std::vector<double> v(delays_.items().begin(), delays_.items().end());
  return static_cast<float>(medianOf(v));
}

std::string ViewDelayMonitor::describe() const {
  const float m = median();
  const auto& delays = delays_.items();
  const auto [lo, hi] = std::minmax_element(delays.begin(), delays.end());
  char line[200];
  std::snprintf(line, sizeof line,
                "the right view is taken %.1f ms %s the left (median of the last %d checks while moving, %.1f to %.1f ms)",
                std::abs(m), m >= 0 ? "after" : "before", samples(), delays.empty() ? 0.0f : *lo,
                delays.empty() ? 0.0f : *hi);
  return line;
}

}  // namespace nerv::stereo

#include "rectification_check.hpp"

#include "percentile.hpp"
#include "textured_points.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
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
                           const RowOffsetParams& p, const RowPlane& applied) {
  RowOffset out;
  if (left.empty() || left.type() != CV_8UC1 || right.size() != left.size() || right.type() != CV_8UC1 ||
      disparity.size() != left.size() || disparity.type() != CV_32FC1)
    return out;
  // The most textured grid points with a disparity whose match lies inside the right view.
  const int r = std::max(1, p.window_px / 2);
  MatchedPoints matched = matchedTexturedPoints(left, disparity, {p.grid_px, p.window_px, p.max_points});
  const std::vector<cv::Point2f>& from = matched.left;
  std::vector<cv::Point2f>& to = matched.right;
  const std::vector<float>& disp = matched.disparity;
  if (static_cast<int>(from.size()) < p.min_points) {
    out.points = static_cast<int>(from.size());
    return out;
  }
  std::vector<uchar> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(left, right, from, to, status, error, cv::Size(2 * r + 1, 2 * r + 1), 2,
                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01),
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<float> dy, u, v;
  dy.reserve(from.size());
  const float cx = 0.5f * static_cast<float>(left.cols), cy = 0.5f * static_cast<float>(left.rows);
  for (size_t i = 0; i < from.size(); ++i) {
    if (!status[i] || !std::isfinite(to[i].x) || !std::isfinite(to[i].y)) continue;
    if (std::abs(to[i].x - (from[i].x - disp[i])) > p.max_horizontal_miss_px) continue;
    dy.push_back(to[i].y - from[i].y);
    u.push_back(from[i].x - cx);
    v.push_back(from[i].y - cy);
  }
  out.points = static_cast<int>(dy.size());
  if (out.points < p.min_points) return out;
  // The plane dy = a + b u + c v, iteratively reweighted least squares with Huber weights
  // (k = 1.345 robust sigmas), from the median as a flat start.
  double a = medianOf(dy), b = 0, c = 0;
  std::vector<float> res(dy.size());
  const auto residuals = [&] {
    for (size_t i = 0; i < dy.size(); ++i) res[i] = static_cast<float>(dy[i] - (a + b * u[i] + c * v[i]));
  };
  for (int iter = 0; iter < 8; ++iter) {
    residuals();
    std::vector<float> abs_res(res.size());
    for (size_t i = 0; i < res.size(); ++i) abs_res[i] = std::abs(res[i]);
    const double scale = std::max(1e-3, 1.4826 * medianOf(abs_res));
    cv::Matx33d ata = cv::Matx33d::zeros();
    cv::Vec3d atb(0, 0, 0);
    for (size_t i = 0; i < dy.size(); ++i) {
      const double r = std::abs(res[i]) / scale, w = r <= 1.345 ? 1.0 : 1.345 / r;
      const cv::Vec3d x(1.0, u[i], v[i]);
      for (int j = 0; j < 3; ++j) {
        atb[j] += w * x[j] * dy[i];
        for (int k = 0; k < 3; ++k) ata(j, k) += w * x[j] * x[k];
      }
    }
    cv::Vec3d sol;
    if (!cv::solve(ata, atb, sol, cv::DECOMP_CHOLESKY)) break;  // points on a line: keep the last
    a = sol[0], b = sol[1], c = sol[2];
  }
  residuals();
  for (float& r : res) r = std::abs(r);
  // What is left in these views, and the rig's plane: the correction they were made with plus that.
  const RowPlane left_over{a, b, c}, rig = applied + left_over;
  const auto worst = [&](const RowPlane& q) {
    std::vector<double> model(dy.size());
    for (size_t i = 0; i < dy.size(); ++i)
      model[i] = static_cast<float>(std::abs(q.offset_px + q.slope_x * u[i] + q.slope_y * v[i]));
    return static_cast<float>(percentile(std::move(model), 0.9));
  };
  out.residual_worst_px = worst(left_over);
  out.worst_px = applied.zero() ? out.residual_worst_px : worst(rig);
  out.offset_px = static_cast<float>(rig.offset_px);
  out.slope_x = static_cast<float>(rig.slope_x);
  out.slope_y = static_cast<float>(rig.slope_y);
  out.spread_px = 1.4826f * medianOf(res);
  out.valid = std::isfinite(out.offset_px) && std::isfinite(out.slope_x) && std::isfinite(out.slope_y);
  return out;
}

bool RowOffsetMonitor::add(const RowOffset& m) { return m.valid && checks_.add(m); }

RowOffset RowOffsetMonitor::median() const {
  RowOffset m;
  if (checks_.size() == 0) return m;
  std::vector<float> a, b, c, worst, residual, spread;
  for (const RowOffset& r : checks_.items()) {
    a.push_back(r.offset_px), b.push_back(r.slope_x), c.push_back(r.slope_y);
    worst.push_back(r.worst_px), residual.push_back(r.residual_worst_px), spread.push_back(r.spread_px);
  }
  m.valid = true;
  m.points = static_cast<int>(checks_.items().back().points);
  m.offset_px = medianOf(a);
  m.slope_x = medianOf(b);
  m.slope_y = medianOf(c);
  m.worst_px = medianOf(worst);
  m.residual_worst_px = medianOf(residual);
  m.spread_px = medianOf(spread);
  return m;
}

std::string RowOffsetMonitor::describe() const {
  const RowOffset m = median();
  int lo = 0, hi = 0;
  const auto& checks = checks_.items();
  for (size_t i = 0; i < checks.size(); ++i) {
    lo = i ? std::min(lo, checks[i].points) : checks[i].points;
    hi = i ? std::max(hi, checks[i].points) : checks[i].points;
  }
  char line[260];
  std::snprintf(line, sizeof line,
                "the right view's rows lie %.2f px %s the left's at its centre and up to %.2f px off where it matches "
                "(turned %.2f deg; median of the last %d checks, %d-%d points each)",
                std::abs(m.offset_px), m.offset_px >= 0 ? "below" : "above", m.worst_px,
                std::atan(m.slope_x) * 180 / CV_PI, samples(), lo, hi);
  return line;
}

}  // namespace nerv::stereo

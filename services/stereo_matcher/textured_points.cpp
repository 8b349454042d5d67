#include "textured_points.hpp"

#include <algorithm>
#include <cmath>

namespace nerv::stereo {

std::vector<cv::Point2f> texturedPoints(const cv::Mat& image, const TexturedPointsParams& p,
                                        const std::function<bool(int x, int y)>& usable) {
  std::vector<cv::Point2f> out;
  const int r = std::max(1, p.window_px / 2);
  const int margin = r + 2;
  if (image.empty() || image.type() != CV_8UC1 || image.cols <= 2 * margin || image.rows <= 2 * margin ||
      p.max_points <= 0)
    return out;
  struct Candidate {
    float score;
    cv::Point2f at;
  };
  std::vector<Candidate> candidates;
  const int step = std::max(2, p.grid_px);
  for (int y = margin; y < image.rows - margin; y += step)
    for (int x = margin; x < image.cols - margin; x += step) {
      if (usable && !usable(x, y)) continue;
      double sxx = 0, syy = 0, sxy = 0;
      for (int v = y - r; v <= y + r; ++v) {
        const uchar* up = image.ptr<uchar>(v - 1);
        const uchar* row = image.ptr<uchar>(v);
        const uchar* down = image.ptr<uchar>(v + 1);
        for (int u = x - r; u <= x + r; ++u) {
          const int gx = row[u + 1] - row[u - 1], gy = down[u] - up[u];
          sxx += gx * gx, syy += gy * gy, sxy += gx * gy;
        }
      }
      const double half_trace = 0.5 * (sxx + syy), half_diff = 0.5 * (sxx - syy);
      const double min_eig = half_trace - std::sqrt(half_diff * half_diff + sxy * sxy);
      if (min_eig > std::max(0.0, p.min_score)) candidates.push_back({static_cast<float>(min_eig), cv::Point2f(x, y)});
    }
  if (static_cast<int>(candidates.size()) > p.max_points) {
    std::nth_element(candidates.begin(), candidates.begin() + p.max_points, candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    candidates.resize(static_cast<size_t>(p.max_points));
  }
  out.reserve(candidates.size());
  for (const Candidate& c : candidates) out.push_back(c.at);
  return out;
}

MatchedPoints matchedTexturedPoints(const cv::Mat& left, const cv::Mat& disparity, const TexturedPointsParams& params) {
  MatchedPoints out;
  if (disparity.size() != left.size() || disparity.type() != CV_32FC1) return out;
  const int margin = std::max(1, params.window_px / 2) + 2;
  for (const cv::Point2f& c : texturedPoints(left, params, [&](int x, int y) {
         const float d = disparity.at<float>(y, x);
         return d > 0 && x - d >= margin;
       })) {
    const float d = disparity.at<float>(cvRound(c.y), cvRound(c.x));
    out.left.push_back(c);
    out.right.push_back({c.x - d, c.y});
    out.disparity.push_back(d);
  }
  return out;
}

}  // namespace nerv::stereo

#include "disparity_metrics.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

namespace nerv::stereo {

void interpolateBackground(cv::Mat& disparity) {
  CV_Assert(disparity.type() == CV_32FC1);
  const int rows = disparity.rows, cols = disparity.cols;
  for (int v = 0; v < rows; ++v) {
    float* d = disparity.ptr<float>(v);
    int first = -1, last = -1;
    for (int u = 0; u < cols; ++u) {
      if (!(d[u] > 0.0f)) continue;
      if (last >= 0 && u - last > 1) {
        const float fill = std::min(d[last], d[u]);  // background: the farther neighbour
        std::fill(d + last + 1, d + u, fill);
      }
      if (first < 0) first = u;
      last = u;
    }
    if (first < 0) continue;
    std::fill(d, d + first, d[first]);
    std::fill(d + last + 1, d + cols, d[last]);
  }
  for (int u = 0; u < cols; ++u) {
    int first = -1, last = -1;
    for (int v = 0; v < rows; ++v)
      if (disparity.at<float>(v, u) > 0.0f) {
        if (first < 0) first = v;
        last = v;
      }
    if (first < 0) continue;
    for (int v = 0; v < first; ++v) disparity.at<float>(v, u) = disparity.at<float>(first, u);
    for (int v = last + 1; v < rows; ++v) disparity.at<float>(v, u) = disparity.at<float>(last, u);
  }
}

namespace {

template <class IsBad>
DisparityScore score(const cv::Mat& estimate, const cv::Mat& gt, IsBad is_bad) {
  CV_Assert(estimate.type() == CV_32FC1 && gt.type() == CV_32FC1 && estimate.size() == gt.size());
  cv::Mat filled = estimate.clone();
  interpolateBackground(filled);
  DisparityScore s;
  long long bad = 0, had_value = 0;
  double inlier_sum = 0, inlier_signed = 0;
  for (int v = 0; v < gt.rows; ++v) {
    const float* g = gt.ptr<float>(v);
    const float* e = estimate.ptr<float>(v);
    const float* f = filled.ptr<float>(v);
    for (int u = 0; u < gt.cols; ++u) {
      if (!(g[u] > 0.0f)) continue;
      ++s.pixels;
      if (e[u] > 0.0f) {
        ++had_value;
        const float err = std::fabs(e[u] - g[u]);
        if (err <= 1.0f) {
          inlier_sum += err;
          inlier_signed += e[u] - g[u];
          ++s.inliers;
        }
      }
      // a map with no valid pixel at all stays 0 after interpolation: all wrong
      if (!(f[u] > 0.0f) || is_bad(std::fabs(f[u] - g[u]), g[u])) ++bad;
    }
  }
  if (s.pixels > 0) {
    s.error_rate = static_cast<double>(bad) / s.pixels;
    s.density = static_cast<double>(had_value) / s.pixels;
  }
  if (s.inliers > 0) {
    s.inlier_mean_error = inlier_sum / static_cast<double>(s.inliers);
    s.inlier_mean_bias = inlier_signed / static_cast<double>(s.inliers);
  }
  return s;
}

}  // namespace

DisparityScore scoreD1(const cv::Mat& estimate, const cv::Mat& gt) {
  return score(estimate, gt, [](float err, float g) { return err > 3.0f && err > 0.05f * g; });
}

DisparityScore scoreBad(const cv::Mat& estimate, const cv::Mat& gt, double threshold_px) {
  const float t = static_cast<float>(threshold_px);
  return score(estimate, gt, [t](float err, float) { return err > t; });
}

cv::Mat loadGroundTruth(const std::string& path, std::string& kind) {
  const cv::Mat raw = cv::imread(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
  if (raw.empty()) CV_Error(cv::Error::StsError, "cannot read ground truth " + path);
  cv::Mat gt;
  if (raw.depth() == CV_16U) {
    kind = "kitti";
    raw.convertTo(gt, CV_32F, 1.0 / 256.0);
  } else {
    kind = "middlebury";
    raw.convertTo(gt, CV_32F);
  }
  return gt;
}

std::vector<EvalFrame> findEvalFrames(const std::string& dir) {
  namespace fs = std::filesystem;
  auto stems = [&](const char* sub) {
    std::map<std::string, std::string> out;
    const fs::path folder = fs::path(dir) / sub;
    if (!fs::is_directory(folder)) return out;
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.is_regular_file()) out[entry.path().stem().string()] = entry.path().string();
    return out;
  };
  // plain layout, else KITTI stereo/object layout
  const bool plain = fs::is_directory(fs::path(dir) / "left");
  const auto left = stems(plain ? "left" : "image_2"), right = stems(plain ? "right" : "image_3"),
             gt = stems(plain ? "disp_gt" : "disp_occ_0");
  std::vector<EvalFrame> frames;
  for (const auto& [name, path] : left) {
    const auto r = right.find(name);
    const auto g = gt.find(name);
    if (r == right.end() || g == gt.end()) continue;
    frames.push_back({name, path, r->second, g->second});
  }
  return frames;
}

}  // namespace nerv::stereo

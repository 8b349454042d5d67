// bench_stereo [--data DIR] [--runs N] [--threads N] [--only NAME]: per algorithm, ms per
// frame (median of N runs, default 11) and the error against ground truth (D1
// for KITTI, bad-2.0 for Middlebury), with each algorithm's time relative to
// OpenCV SGBM 3-way (block 5, P1 8*25, P2 32*25, 128 levels) measured in the
// same run. Default data: ../shared/data/kitti2015_000005.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "disparity_metrics.hpp"
#include "stereo_matcher.hpp"

using namespace nerv::stereo;

int main(int argc, char** argv) {
  std::string data = std::string(NERV_SHARED_DATA) + "/kitti2015_000005";
  int runs = 11;
  int threads = 2;
  std::string only;  // run the baseline and this algorithm only
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_stereo [--data DIR] [--runs N] [--threads N] [--only ALGORITHM]\n");
      return 2;
    }
  }
  const std::vector<EvalFrame> frames = findEvalFrames(data);
  if (frames.empty()) {
    std::fprintf(stderr, "bench_stereo: no left/right/disp_gt frames in %s\n", data.c_str());
    return 1;
  }
  const EvalFrame& f = frames.front();
  cv::Mat left = cv::imread(f.left_path, cv::IMREAD_GRAYSCALE);
  cv::Mat right = cv::imread(f.right_path, cv::IMREAD_GRAYSCALE);
  std::string kind;
  const cv::Mat gt = loadGroundTruth(f.gt_path, kind);
  const char* metric = kind == "kitti" ? "D1" : "bad-2.0";
  std::printf("data %s frame %s (%dx%d), %d runs, median; metric %s after background "
              "interpolation\n", data.c_str(), f.name.c_str(), left.cols, left.rows, runs, metric);

  struct Entry { std::string label; Params params; };
  std::vector<Entry> entries;
  auto add = [&](const std::string& label, const std::string& algorithm, int downscale = 1) {
    Params p;
    p.algorithm = algorithm;
    p.downscale = downscale;
    p.threads = threads;
    if (entries.empty() || only.empty() || only == algorithm) entries.push_back({label, p});
  };
  add("sgbm (baseline)", "sgbm");
  add("bm", "bm");
  add("sgbm_full", "sgbm_full");
  add("sgbm_wls", "sgbm_wls");
  add("nerv_sgm", "nerv_sgm");
  add("nerv_sgm downscale 2", "nerv_sgm", 2);

  double baseline_ms = 0;
  std::printf("%-22s %9s %7s %8s %8s\n", "algorithm", "ms", "ratio", metric, "density");
  for (const Entry& e : entries) {
    auto matcher = StereoMatcher::create(e.params);
    cv::Mat disparity, confidence;
    matcher->compute(left, right, disparity, confidence);  // warm-up (allocations)
    std::vector<double> ms;
    for (int r = 0; r < runs; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      matcher->compute(left, right, disparity, confidence);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    const double median = ms[ms.size() / 2];
    if (baseline_ms == 0) baseline_ms = median;
    const DisparityScore s = kind == "kitti" ? scoreD1(disparity, gt) : scoreBad(disparity, gt, 2.0);
    std::printf("%-22s %9.1f %7.2f %7.2f%% %7.1f%%\n", e.label.c_str(), median, median / baseline_ms,
                100.0 * s.error_rate, 100.0 * s.density);
  }
  return 0;
}

// bench_stereo [--data DIR] [--runs N] [--threads N] [--only NAME]: per algorithm, ms per
// frame (median of N interleaved runs, default 11) and the error against ground truth (D1
// for KITTI, bad-2.0 for Middlebury), with each algorithm's time relative to
// OpenCV SGBM 3-way (block 5, P1 8*25, P2 32*25, 128 levels) measured in the
// same run. Default data: ../shared/data/kitti2015_000005.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "disparity_metrics.hpp"
#include "disparity_offset.hpp"
#include "rig_check.hpp"
#include "shutter_sync.hpp"
#include "own_sgm.hpp"
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
  std::printf("nerv_sgm: %s\n", nerv::stereo::ownSgmCodePaths());

  struct Entry { std::string label; Params params; };
  std::vector<Entry> entries;
  auto add = [&](const std::string& label, const std::string& algorithm, int downscale = 1, int snap = -1,
                 bool near_field = true) {
    Params p;
    p.algorithm = algorithm;
    p.downscale = downscale;
    p.boundary_snap_px = snap;
    p.near_field = near_field;
    p.threads = threads;
    if (entries.empty() || only.empty() || only == algorithm) entries.push_back({label, p});
  };
  add("sgbm (baseline)", "sgbm");
  add("bm", "bm");
  add("sgbm_full", "sgbm_full");
  add("sgbm_wls", "sgbm_wls");
  add("nerv_sgm", "nerv_sgm");
  add("nerv_sgm downscale 2", "nerv_sgm", 2);
  add("nerv_sgm no snap", "nerv_sgm", 1, 0);  // without the fattening correction (boundary_snap.hpp)
  add("nerv_sgm no near field", "nerv_sgm", 1, -1, false);  // without the quarter-resolution match (near_field.hpp)

  // Runs are interleaved (one frame of every algorithm per round) so that load
  // from other processes on a shared computer hits all algorithms alike.
  std::vector<std::unique_ptr<StereoMatcher>> matchers;
  std::vector<cv::Mat> disparities(entries.size()), confidences(entries.size());
  std::vector<std::vector<double>> ms(entries.size()), cpu_ms(entries.size());
  // CPU time of the whole process (all threads): less sensitive to other
  // processes than wall time, shows how much of the machine a frame takes.
  auto cpu_now = [] {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
  };
  for (size_t i = 0; i < entries.size(); ++i) {
    matchers.push_back(StereoMatcher::create(entries[i].params));
    matchers[i]->compute(left, right, disparities[i], confidences[i]);  // warm-up (allocations)
  }
  for (int r = 0; r < runs; ++r)
    for (size_t i = 0; i < entries.size(); ++i) {
      const double c0 = cpu_now();
      const auto t0 = std::chrono::steady_clock::now();
      matchers[i]->compute(left, right, disparities[i], confidences[i]);
      ms[i].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      cpu_ms[i].push_back(cpu_now() - c0);
    }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const double baseline_ms = median(ms[0]);
  std::printf("%-22s %9s %7s %9s %8s %8s\n", "algorithm", "ms", "ratio", "cpu ms", metric, "density");
  for (size_t i = 0; i < entries.size(); ++i) {
    const double m = median(ms[i]);
    const DisparityScore s = kind == "kitti" ? scoreD1(disparities[i], gt) : scoreBad(disparities[i], gt, 2.0);
    std::printf("%-22s %9.1f %7.2f %9.1f %7.2f%% %7.1f%%\n", entries[i].label.c_str(), m, m / baseline_ms,
                median(cpu_ms[i]), 100.0 * s.error_rate, 100.0 * s.density);
  }
  // The stereo_matcher's rectification check (rectification_check.hpp) on the default
  // matcher's disparity (else the last entry's): what one check costs, and the rows it reads.
  size_t checked = entries.size() - 1;
  for (size_t i = 0; i < entries.size(); ++i)
    if (entries[i].label == "nerv_sgm") checked = i;
  // The median wall time of body(r) over max(runs, 5) runs [ms].
  const auto median_ms = [&](auto&& body) {
    std::vector<double> t;
    for (int r = 0; r < std::max(runs, 5); ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      body(r);
      t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    return median(t);
  };
  RowOffset offset;
  const double check_ms = median_ms([&](int) { offset = measureRowOffset(left, right, disparities[checked]); });
  const int every = RigCheckParams{}.check_every;
  std::printf("rectification check on %s's disparity: %.2f ms (every %dth frame by default: %.2f ms a frame); "
              "rows %+.2f px at the centre, up to %.2f px off, turned %.3f deg, from %d points%s\n",
              entries[checked].label.c_str(), check_ms, every, check_ms / every, offset.offset_px,
              offset.worst_px, std::atan(offset.slope_x) * 180 / CV_PI, offset.points,
              offset.valid ? "" : " (no measurement)");
  // The row correction (view_correction.hpp) of a rig knocked by that much: its right view resampled
  // on every frame before matching, only while a verdict found the rows off.
  {
    ViewCorrection correction;
    correction.setRows({0.5, 0.001, 0.0005});
    correction.apply(right);  // the maps, built once per correction
    std::printf("row correction (only on a rig whose rows are off): %.2f ms a frame\n",
                median_ms([&](int) { correction.apply(right); }));
    // The offset correction: the offset taken off every disparity, each run on its own copy of the matcher's.
    ViewCorrection offset;
    offset.setColumns(0.5);
    std::vector<cv::Mat> copies(static_cast<size_t>(std::max(runs, 5)));
    for (cv::Mat& d : copies) d = disparities[checked].clone();
    std::printf("offset correction (only on a rig whose disparity is offset): %.2f ms a frame\n",
                median_ms([&](int r) { offset.correctDisparity(copies[static_cast<size_t>(r)]); }));
  }
  // The checks against the vehicle's motion (shutter_sync.hpp, disparity_offset.hpp) on the same
  // frames: one pair has no earlier frame, so the left view stands in for it. That costs the
  // same tracking and fits, and reads nothing (no motion).
  bool read_something = false;
  const double motion_ms = median_ms([&](int) {
    const MotionTracks tracks = trackMotion(left, left, disparities[checked]);
    const ShutterSync sync = measureShutterSync(tracks, left, right, 721.5, left.cols / 2.0, left.rows / 2.0);
    const DisparityOffset shift = measureDisparityOffset(tracks, 721.5, left.cols / 2.0, left.rows / 2.0);
    read_something = read_something || sync.valid || shift.valid;
  });
  if (read_something) std::printf("motion checks: a reading without motion\n");
  std::printf("checks against the motion (shutters, disparity offset) on the same frames: %.2f ms (%.2f ms a frame)\n",
              motion_ms, motion_ms / every);
  return 0;
}

// nerv_eval_disparity: score disparity maps against ground truth.
//
//   nerv_eval_disparity --data DIR [--algorithm NAME ...] [--config FILE]
//   nerv_eval_disparity --data DIR --log LOG [--channel DISPARITY] [--from-seq N]
//
// DIR holds left/, right/ and disp_gt/ (or KITTI image_2/, image_3/, disp_occ_0/,
// as the synthetic generator writes; same stems). With --algorithm (repeat it
// to compare; default: the configured or built-in algorithm) each frame is
// matched here; with --log the DISPARITY events of an LCM log are scored, each
// against the frame its header.frame_id names (the whole id, or its last part after a '/', as
// nerv_source sends "<folder>/<frame>"), each seq once, from seq N on with --from-seq. KITTI ground truth (16-bit) is
// scored with D1 (|d - gt| > 3 px and > 5 %), Middlebury (8-bit) with bad-2.0;
// both after the KITTI devkit's background interpolation, with the density of
// the estimate and "subpx", the mean |d - gt| over its valid pixels within 1 px
// of the truth (subpixel accuracy), and "bias", their mean d - gt (a disparity offset: a rig
// turned since calibration, or the matcher's own). Matching here, it also prints the stereo_matcher's
// rectification check over the frames (rectification_check.hpp): how far the right view's
// rows are off, the median of the frames, so a badly rectified set shows before its scores
// are blamed on a matcher. Exit 0 on success, 2 on bad arguments or unreadable input.
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "config.hpp"
#include "pipeline_keys.hpp"
#include "rig_check.hpp"
#include "disparity_metrics.hpp"
#include "frame_name.hpp"
#include "message_convert.hpp"
#include "stereo_matcher.hpp"

using namespace nerv;
using namespace nerv::stereo;

namespace {

struct Totals {
  long long pixels = 0;
  double bad = 0, valid = 0, ms = 0, inlier_error = 0, inlier_bias = 0;
  long long inliers = 0;
  int frames = 0;
  std::string metric;
  void add(const DisparityScore& s, double frame_ms, const std::string& m) {
    pixels += s.pixels;
    bad += s.error_rate * s.pixels;
    valid += s.density * s.pixels;
    inlier_error += s.inlier_mean_error * static_cast<double>(s.inliers);
    inlier_bias += s.inlier_mean_bias * static_cast<double>(s.inliers);
    inliers += s.inliers;
    ms += frame_ms;
    ++frames;
    metric = m;
  }
};

DisparityScore scoreFrame(const cv::Mat& disparity, const cv::Mat& gt, const std::string& kind) {
  return kind == "kitti" ? scoreD1(disparity, gt) : scoreBad(disparity, gt, 2.0);
}

void printRow(const std::string& label, const Totals& t) {
  if (t.frames == 0 || t.pixels == 0) {
    std::printf("%-20s no frame scored\n", label.c_str());
    return;
  }
  const double n = t.inliers ? static_cast<double>(t.inliers) : 1.0;
  std::printf("%-20s %6d %-8s %8.2f%% %8.1f%% %9.3f %+9.3f %9.1f\n", label.c_str(), t.frames,
              t.metric.c_str(), 100.0 * t.bad / t.pixels, 100.0 * t.valid / t.pixels, t.inlier_error / n,
              t.inlier_bias / n, t.ms / t.frames);
}

int usage(const char* why) {
  std::fprintf(stderr,
               "nerv_eval_disparity: %s\nusage: nerv_eval_disparity --data DIR [--algorithm NAME ...] "
               "[--config FILE] | --data DIR --log LOG [--channel NAME] [--from-seq N]\n",
               why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data, log, config_path, channel = "DISPARITY";
  long long from_seq = 0;
  std::vector<std::string> algorithms;
  for (int i = 1; i < argc; ++i) {
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (!std::strcmp(argv[i], "--data") && (v = value())) data = v;
    else if (!std::strcmp(argv[i], "--algorithm") && (v = value())) algorithms.push_back(v);
    else if (!std::strcmp(argv[i], "--config") && (v = value())) config_path = v;
    else if (!std::strcmp(argv[i], "--log") && (v = value())) log = v;
    else if (!std::strcmp(argv[i], "--channel") && (v = value())) channel = v;
    else if (!std::strcmp(argv[i], "--from-seq") && (v = value())) from_seq = std::atoll(v);
    else return usage((std::string("bad argument '") + argv[i] + "'").c_str());
  }
  if (data.empty()) return usage("--data DIR is required");
  const std::vector<EvalFrame> frames = findEvalFrames(data);
  if (frames.empty()) return usage(("no left/right/disp_gt frames in " + data).c_str());

  std::map<std::string, std::pair<cv::Mat, std::string>> truth;  // name -> (gt, kind)
  try {
    for (const EvalFrame& f : frames) {
      std::string kind;
      cv::Mat gt = loadGroundTruth(f.gt_path, kind);
      truth[f.name] = {gt, kind};
    }
  } catch (const cv::Exception& e) {
    return usage(e.err.c_str());
  }
  auto metricName = [](const std::string& kind) { return kind == "kitti" ? "D1" : "bad-2.0"; };
  std::printf("%-20s %6s %-8s %9s %9s %9s %9s %9s\n", "algorithm", "frames", "metric", "error",
              "density", "subpx", "bias", "ms/frame");

  if (!log.empty()) {
    lcm::LogFile file(log, "r");
    if (!file.good()) return usage(("cannot open log " + log).c_str());
    std::map<std::string, Totals> by_algorithm;
    int undecodable = 0, unknown = 0;
    std::set<int64_t> scored;  // a replayed or duplicated frame counts once
    while (const lcm::LogEvent* event = file.readNextEvent()) {
      if (event->channel != channel) continue;
      disparity_t msg;
      cv::Mat disparity;
      if (msg.decode(event->data, 0, event->datalen) < 0 || !decodeDisparity(msg, disparity).empty()) {
        ++undecodable;
        continue;
      }
      if (msg.header.seq < from_seq || !scored.insert(msg.header.seq).second) continue;
      auto it = truth.find(msg.header.frame_id);
      if (it == truth.end()) it = truth.find(frameName(msg.header.frame_id));
      if (it == truth.end() || it->second.first.size() != disparity.size()) {
        ++unknown;
        continue;
      }
      by_algorithm[msg.algorithm].add(scoreFrame(disparity, it->second.first, it->second.second),
                                      msg.processing_ms, metricName(it->second.second));
    }
    for (const auto& [name, totals] : by_algorithm) printRow(name, totals);
    if (undecodable || unknown)
      std::printf("skipped: %d undecodable, %d naming no ground-truth frame of the same size\n",
                  undecodable, unknown);
    return by_algorithm.empty() ? 1 : 0;
  }

  Params base;
  try {
    if (!config_path.empty()) {
      YAML::Node root = loadConfigFile(config_path);
      ConfigSection section(root["stereo_matcher"], "stereo_matcher");
      allowServiceOnlyKeys(section, "stereo_matcher");
      base = readParams(section);
      section.finish();
    }
    if (algorithms.empty()) algorithms.push_back(base.algorithm);
    // On the first algorithm's disparity, against the service's default limit.
    const float max_row_offset = RigCheckParams{}.max_row_offset_px;
    RowOffsetMonitor rows(static_cast<int>(frames.size()), max_row_offset);
    bool rows_checked = false;
    for (const std::string& name : algorithms) {
      Params p = base;
      p.algorithm = name;
      auto matcher = StereoMatcher::create(p);
      Totals totals;
      for (const EvalFrame& f : frames) {
        const cv::Mat left = cv::imread(f.left_path, cv::IMREAD_GRAYSCALE);
        const cv::Mat right = cv::imread(f.right_path, cv::IMREAD_GRAYSCALE);
        const auto& [gt, kind] = truth[f.name];
        if (left.empty() || right.empty() || left.size() != right.size() || gt.size() != left.size()) {
          std::fprintf(stderr, "nerv_eval_disparity: frame %s: unreadable or sizes differ, skipped\n",
                       f.name.c_str());
          continue;
        }
        cv::Mat disparity, confidence;
        const auto t0 = std::chrono::steady_clock::now();
        matcher->compute(left, right, disparity, confidence);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        totals.add(scoreFrame(disparity, gt, kind), ms, metricName(kind));
        if (!rows_checked) rows.add(measureRowOffset(left, right, disparity));
      }
      printRow(matcher->name(), totals);
      rows_checked = true;
    }
    if (rows.samples() > 0)
      std::printf("rectification check (the stereo_matcher's, on %d frames): %s%s\n", rows.samples(),
                  rows.describe().c_str(),
                  rows.misaligned() ? cv::format(": MISALIGNED beyond %.2f px", max_row_offset).c_str() : ": aligned");
    else
      std::printf("rectification check: no frame with enough textured points\n");
  } catch (const ConfigError& e) {
    return usage(e.what());
  }
  return 0;
}

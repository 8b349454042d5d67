// Stixel stage timing: estimateStixels (ground fit + free space + stixels +
// hypotheses) against the plain per-column reference (stixel_reference.hpp) on
// the same disparities, measured in the same run.
//   build/bin/bench_stixel [runs] [--data DIR]
// Uses the disparities of ../shared/data/kitti_raw_0926_seq when present, twice:
// OpenCV SGBM's (the figure of earlier rounds) and then nerv_sgm's as the
// stixel service receives them (the pipeline's default matcher, through the
// DISPARITY message's 1/256 px; denser, so more obstacle pixels to scan);
// otherwise rendered synthetic scenes. --data DIR: the frames of that folder (a KITTI-style
// set, e.g. build/synthetic_sets/urban_11_30) with nerv_sgm's disparities only.
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "dataset.hpp"
#include "message_convert.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "stixel_reference.hpp"
#include "synthetic_road_scene.hpp"

using namespace nerv;
using namespace nerv::stixel;

namespace {

struct Input {
  std::string name;
  cv::Mat disparity;
  StereoCamera cam;
};

cv::Mat sgbm(const std::string& left, const std::string& right) {
  auto m = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 0, 0, 0, 0, 0,
                                  cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat raw, d;
  m->compute(cv::imread(left, cv::IMREAD_GRAYSCALE), cv::imread(right, cv::IMREAD_GRAYSCALE), raw);
  raw.convertTo(d, CV_32F, 1.0 / 16.0);
  d.setTo(0.0f, d < 0.0f);
  return d;
}

// nerv_sgm with the pipeline's defaults, encoded and decoded as the DISPARITY
// message carries it to the stixel service.
cv::Mat nervSgm(stereo::StereoMatcher& m, const std::string& left, const std::string& right) {
  cv::Mat d, out;
  m.compute(cv::imread(left, cv::IMREAD_GRAYSCALE), cv::imread(right, cv::IMREAD_GRAYSCALE), d);
  disparity_t msg;
  encodeDisparity(d, "u16le", msg);
  const std::string error = decodeDisparity(msg, out);
  if (!error.empty()) throw std::runtime_error("bench_stixel: " + left + ": " + error);
  return out;
}

// The frames of a dataset folder (default KITTI 0926) with SGBM's disparities (nerv_sgm =
// false) or nerv_sgm's; empty without the data.
std::vector<Input> loadFolder(bool nerv_sgm, std::string dir = "") {
  std::vector<Input> in;
  if (dir.empty()) dir = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  if (!std::filesystem::exists(dir)) return in;
  std::unique_ptr<stereo::StereoMatcher> m = stereo::StereoMatcher::create(stereo::Params{});
  for (const DatasetFrame& f : openDataset(dir).frames)
    in.push_back({f.name, nerv_sgm ? nervSgm(*m, f.left_path, f.right_path) : sgbm(f.left_path, f.right_path), f.camera});
  return in;
}

std::vector<Input> loadSynthetic() {
  std::vector<Input> in;
  const StereoCamera cam = kittiLikeCamera();
  for (int i = 0; i < 4; ++i) {
    RoadScene s;
    s.pitch_deg = -0.5f + 0.3f * i;
    s.boxes = {{8.0f + i, -4.0f, -2.0f, 1.5f}, {18.0f, -1.0f, 1.0f, 1.5f}, {30.0f - i, 3.0f, 7.0f, 2.5f}};
    in.push_back({"synthetic_" + std::to_string(i), renderDisparity(s, cam), cam});
  }
  return in;
}

template <class F>
double medianMs(int runs, F&& f) {
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

// Times every input; prints a row per frame and returns the median line.
std::string timeInputs(const std::vector<Input>& inputs, int runs, const Params& params, size_t& sink) {
  std::printf("frame        size       fast_ms  reference_ms  ratio  stixels  hypotheses\n");
  std::vector<double> fast_all, ref_all;
  for (const Input& in : inputs) {
    StixelResult res;
    const double fast = medianMs(runs, [&] { res = estimateStixels(in.disparity, in.cam, params); });
    // The reference starts from the ground model the fast path found (it has no
    // ground fit of its own); its time is the per-column stixel extraction only.
    const double ref = res.ground.valid
        ? medianMs(runs, [&] { sink += referenceStixels(in.disparity, in.cam, res.ground, params).size(); })
        : 0.0;
    fast_all.push_back(fast);
    ref_all.push_back(ref);
    std::printf("%-12s %4dx%-4d  %7.3f  %12.3f  %5.1f  %7zu  %10zu\n", in.name.c_str(),
                in.disparity.cols, in.disparity.rows, fast, ref, fast > 0 ? ref / fast : 0.0,
                res.stixels.size(), res.hypotheses.size());
  }
  std::sort(fast_all.begin(), fast_all.end());
  std::sort(ref_all.begin(), ref_all.end());
  const double f = fast_all[fast_all.size() / 2], r = ref_all[ref_all.size() / 2];
  char line[256];
  std::snprintf(line, sizeof line,
                "median over %zu frames (%d runs each): estimateStixels %.3f ms/frame (%.0f fps), "
                "per-column reference %.3f ms/frame, ratio %.1fx",
                inputs.size(), runs, f, 1000.0 / f, r, r / f);
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 25;
  std::string data;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--data" && i + 1 < argc) {
      data = argv[++i];
    } else if (!a.empty() && std::isdigit(static_cast<unsigned char>(a[0]))) {
      runs = std::max(1, std::atoi(a.c_str()));
    } else {
      std::fprintf(stderr, "usage: bench_stixel [runs] [--data DIR]\n");
      return 2;
    }
  }
  const Params params;
  size_t sink = 0;
  if (!data.empty()) {  // one folder, nerv_sgm's disparities only
    const std::vector<Input> inputs = loadFolder(true, data);
    if (inputs.empty()) {
      std::fprintf(stderr, "bench_stixel: no frames in %s\n", data.c_str());
      return 2;
    }
    std::printf("disparity: nerv_sgm through the DISPARITY message, %s\n", data.c_str());
    std::printf("%s\n", timeInputs(inputs, runs, params, sink).c_str());
    return sink == 0 ? 0 : 0;
  }
  const std::vector<Input> sgbm_inputs = loadFolder(false);
  if (sgbm_inputs.empty()) {
    std::printf("%s\n", timeInputs(loadSynthetic(), runs, params, sink).c_str());
    return 0;
  }
  std::printf("disparity: OpenCV SGBM (as in earlier rounds)\n");
  const std::string sgbm_line = timeInputs(sgbm_inputs, runs, params, sink);
  std::printf("%s\n\ndisparity: nerv_sgm through the DISPARITY message (the pipeline's default)\n", sgbm_line.c_str());
  const std::string nerv_line = timeInputs(loadFolder(true), runs, params, sink);
  std::printf("%s\n\nSGBM:     %s\nnerv_sgm: %s\n", nerv_line.c_str(), sgbm_line.c_str(), nerv_line.c_str());
  return sink == 0 ? 0 : 0;
}

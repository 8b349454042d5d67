// Stixel stage timing: estimateStixels (ground fit + free space + stixels +
// hypotheses) against the plain per-column reference (stixel_reference.hpp) on
// the same disparities, measured in the same run.
//   build/bin/bench_stixel [runs]
// Uses SGBM disparities of ../shared/data/kitti_raw_0926_seq when present,
// otherwise rendered synthetic scenes.
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "dataset.hpp"
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

std::vector<Input> loadInputs() {
  std::vector<Input> in;
  const std::string dir = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  if (std::filesystem::exists(dir)) {
    for (const DatasetFrame& f : openDataset(dir).frames)
      in.push_back({f.name, sgbm(f.left_path, f.right_path), f.camera});
    return in;
  }
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

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 25;
  const std::vector<Input> inputs = loadInputs();
  const Params params;
  std::printf("frame        size       fast_ms  reference_ms  ratio  stixels  hypotheses\n");
  std::vector<double> fast_all, ref_all;
  size_t sink = 0;
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
  std::printf("median over %zu frames (%d runs each): estimateStixels %.3f ms/frame (%.0f fps), "
              "per-column reference %.3f ms/frame, ratio %.1fx\n",
              inputs.size(), runs, f, 1000.0 / f, r, r / f);
  return sink == 0 ? 0 : 0;
}

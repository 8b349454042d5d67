// Benchmark of validator::validate() for 50 hypotheses per frame against a
// naive version (linear search for each hypothesis' statistics, reasons built
// with ostringstream) measured in the same run.
// Usage: bench_validator [frames=20000]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <thread>

#include "validator.hpp"

using namespace nerv;
using Clock = std::chrono::steady_clock;

namespace {

// Naive baseline: same rules, O(N*M) matching and stream formatting.
std::vector<Verdict> naiveValidate(const std::vector<Hypothesis>& hyps,
                                   const std::vector<NormalStats>& stats,
                                   const validator::Params& p) {
  std::vector<Verdict> out;
  for (const Hypothesis& h : hyps) {
    const NormalStats* match = nullptr;
    for (const NormalStats& s : stats)
      if (s.roi_id == h.id && match == nullptr) match = &s;
    Verdict v;
    v.roi_id = h.id;
    std::ostringstream why;
    if (match == nullptr || match->num_normals < p.min_normals) {
      v.label = "unvalidated";
      v.kept = p.keep_unvalidated;
      why << "unvalidated: no normals";
    } else if (match->ground_fraction > p.max_ground_fraction) {
      v.label = "ground";
      why << "ground normals " << static_cast<int>(match->ground_fraction * 100 + 0.5f) << "%";
    } else if (match->error_fraction > p.max_error_fraction) {
      v.label = "error";
      why << "error-like normals " << static_cast<int>(match->error_fraction * 100 + 0.5f) << "%";
    } else {
      v.label = "object";
      v.kept = true;
    }
    v.reason = why.str();
    out.push_back(v);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20000;
  const int n = 50;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::vector<Hypothesis> hyps(n);
  std::vector<NormalStats> stats;
  for (int i = 0; i < n; ++i) {
    hyps[i].id = 1000 + i;
    hyps[i].height_m = 0.5f + 2.0f * uni(rng);
    hyps[i].width_m = 0.5f + 2.0f * uni(rng);
    if (i % 10 == 9) continue;  // some without statistics
    NormalStats s;
    s.roi_id = hyps[i].id;
    s.num_samples = 400;
    s.num_normals = static_cast<int>(400 * uni(rng));
    s.density = s.num_normals / 400.0f;
    const float a = uni(rng), b = uni(rng) * (1 - a);
    s.ground_fraction = a;
    s.object_fraction = b;
    s.error_fraction = 1 - a - b;
    stats.push_back(s);
  }
  std::shuffle(stats.begin(), stats.end(), rng);
  const validator::Params p;

  size_t sink = 0;
  auto run = [&](auto&& fn) {
    const auto t0 = Clock::now();
    for (int f = 0; f < frames; ++f) sink += fn().size();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / frames;
  };
  run([&] { return validator::validate(hyps, stats, p); });  // warm-up
  const double fast = run([&] { return validator::validate(hyps, stats, p); });
  const double naive = run([&] { return naiveValidate(hyps, stats, p); });
  std::printf("bench_validator: %d hypotheses (%zu with statistics), %d frames, %u hardware threads\n",
              n, stats.size(), frames, std::thread::hardware_concurrency());
  std::printf("validate():        %.4f ms/frame (%.1f us per hypothesis)\n", fast, fast * 1000 / n);
  std::printf("naive baseline:    %.4f ms/frame (linear id search, ostringstream reasons)\n", naive);
  std::printf("ratio naive/fast:  %.2f   target <= 0.5 ms/frame: %s\n", naive / fast,
              fast <= 0.5 ? "met" : "NOT met");
  return sink == 0 ? 1 : 0;
}

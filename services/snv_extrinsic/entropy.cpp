#include "entropy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_mean_shift.hpp"
#include "super_snv.hpp"

namespace nerv::snv {

float windowEntropyBits(const std::vector<float>& sorted, float centre, float fraction,
                        float bin_deg) {
  if (sorted.empty()) throw std::invalid_argument("windowEntropyBits: empty sample");
  const int n = static_cast<int>(sorted.size());
  const int count = std::clamp(static_cast<int>(std::ceil(fraction * n)), 1, n);
  const int b = nearestRunBegin(sorted, centre, count);
  // Bins of bin_deg centred on the estimate; the run is sorted, so equal bins
  // are consecutive: count run lengths.
  auto binOf = [&](float x) { return static_cast<long long>(std::floor((x - centre) / bin_deg + 0.5)); };
  double h = 0;
  int run = 0;
  long long bin = binOf(sorted[b]);
  auto flush = [&]() {
    const double p = static_cast<double>(run) / count;
    h -= p * std::log2(p);
  };
  for (int i = b; i < b + count; ++i) {
    const long long k = binOf(sorted[i]);
    if (k != bin) {
      flush();
      bin = k;
      run = 0;
    }
    ++run;
  }
  flush();
  return static_cast<float>(std::max(0.0, h));
}

float sampleEntropyBits(std::vector<float>& values, float bin) {
  if (values.empty() || !(bin > 0)) return 0.0f;
  sortAngles(values);
  const double n = static_cast<double>(values.size());
  auto binOf = [&](float x) { return static_cast<long long>(std::floor(x / bin + 0.5f)); };
  double h = 0;
  long long cur = binOf(values[0]);
  size_t run = 0;
  for (float x : values) {
    const long long k = binOf(x);
    if (k != cur) {
      h -= run / n * std::log2(run / n);
      cur = k;
      run = 0;
    }
    ++run;
  }
  h -= run / n * std::log2(run / n);
  return static_cast<float>(std::max(0.0, h));
}

float entropyConfidence(float entropy_bits, float full_scale_bits) {
  if (!(full_scale_bits > 0)) return 0.0f;
  return std::clamp(1.0f - entropy_bits / full_scale_bits, 0.0f, 1.0f);
}

}  // namespace nerv::snv

#include "adaptive_mean_shift.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nerv::snv {
namespace {

// Sum of x[0, n) in double over 8 independent lanes (vectorises; the
// single-accumulator loop does not without reassociation).
double windowSum(const float* x, int n) {
  constexpr int kLanes = 8;
  double lane[kLanes] = {0, 0, 0, 0, 0, 0, 0, 0};
  int i = 0;
  for (; i + kLanes <= n; i += kLanes)
    for (int j = 0; j < kLanes; ++j) lane[j] += x[i + j];
  double sum = 0;
  for (; i < n; ++i) sum += x[i];
  for (int j = 0; j < kLanes; ++j) sum += lane[j];
  return sum;
}

}  // namespace

int nearestRunBegin(const std::vector<float>& sorted, float centre, int count) {
  // Classic "k closest elements": the run [i, i+count) is better than
  // [i+1, i+count+1) while centre - x[i] <= x[i+count] - centre.
  int lo = 0, hi = static_cast<int>(sorted.size()) - count;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (centre - sorted[mid] > sorted[mid + count] - centre)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

MeanShiftResult adaptiveMeanShift(const std::vector<float>& sorted, float start, float fraction,
                                  float stop, int max_iterations) {
  if (sorted.empty()) throw std::invalid_argument("adaptiveMeanShift: empty sample");
  const int n = static_cast<int>(sorted.size());
  const int count = std::clamp(static_cast<int>(std::ceil(fraction * n)), 1, n);
  // The window sum is read directly (vectorised, a few iterations of n/2 adds):
  // cheaper than a prefix-sum array, whose n dependent double adds and
  // allocation dominated the few O(log n) iterations.

  MeanShiftResult res;
  res.start = start;
  double centre = start;
  for (res.iterations = 1; res.iterations <= max_iterations; ++res.iterations) {
    const int b = nearestRunBegin(sorted, static_cast<float>(centre), count);
    const double mean = windowSum(sorted.data() + b, count) / count;
    res.radius = static_cast<float>(std::max(centre - sorted[b], sorted[b + count - 1] - centre));
    const double moved = std::abs(mean - centre);
    centre = mean;
    if (moved < stop) {
      res.converged = true;
      break;
    }
  }
  res.iterations = std::min(res.iterations, max_iterations);
  res.estimate = static_cast<float>(centre);
  res.inliers = count;
  return res;
}

}  // namespace nerv::snv

#include "speckle_filter.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace nerv::stereo {

namespace {

// Root of run r, halving the path on the way (union-find).
int findRoot(std::vector<int>& parent, int r) {
  while (parent[static_cast<size_t>(r)] != r) {
    const int up = parent[static_cast<size_t>(parent[static_cast<size_t>(r)])];
    parent[static_cast<size_t>(r)] = up;
    r = up;
  }
  return r;
}

}  // namespace

// OpenCV's filterSpeckles (newVal 0) invalidates every connected region -
// 4-neighbours, both non-zero, differing by at most maxDiff - of at most
// maxSpeckleSize pixels; it grows each region with a flood fill. The regions
// do not depend on how they are found, so they are found here as runs of a
// row joined to the runs above with union-find, which visits each pixel
// twice in plain row order instead of pushing it on a stack (same output,
// tests/unit/test_stereo_speckle_filter.cpp).
void removeSpeckles(cv::Mat& disparity, cv::Mat* confidence, int window_px, int range_px,
                    int row_begin, int row_end, SpeckleScratch& scratch) {
  if (window_px <= 0 || row_end <= row_begin) return;
  CV_Assert(disparity.type() == CV_32FC1);
  cv::Mat stripe = disparity.rowRange(row_begin, row_end);
  cv::Mat& fixed = scratch.fixed;
  stripe.convertTo(fixed, CV_16S, 16.0);  // 1/16 px steps, as OpenCV's matchers
  const int rows = stripe.rows, cols = stripe.cols, max_diff = range_px * 16;
  scratch.labels.create(rows, cols, CV_32S);
  std::vector<int>& parent = scratch.parent;
  std::vector<int>& begin = scratch.run_begin;  // first pixel of each run (y * cols + x)
  std::vector<int>& length = scratch.run_length;
  parent.clear();
  begin.clear();
  length.clear();
  for (int y = 0; y < rows; ++y) {
    const int16_t* f = fixed.ptr<int16_t>(y);
    int* run = scratch.labels.ptr<int>(y);  // run of each pixel, -1 where invalid
    int current = -1;
    for (int x = 0; x < cols; ++x) {
      if (f[x] == 0) {
        run[x] = current = -1;
        continue;
      }
      if (current < 0 || std::abs(f[x] - f[x - 1]) > max_diff) {
        current = static_cast<int>(parent.size());
        parent.push_back(current);
        begin.push_back(y * cols + x);
        length.push_back(0);
      }
      ++length[static_cast<size_t>(current)];
      run[x] = current;
    }
    if (y == 0) continue;
    const int16_t* f_up = fixed.ptr<int16_t>(y - 1);
    const int* run_up = scratch.labels.ptr<int>(y - 1);
    int last_a = -1, last_b = -1;  // the pair joined last (runs overlap over many columns)
    for (int x = 0; x < cols; ++x) {
      const int a = run[x], b = run_up[x];
      if (a < 0 || b < 0 || (a == last_a && b == last_b) || std::abs(f[x] - f_up[x]) > max_diff) continue;
      last_a = a, last_b = b;
      const int ra = findRoot(parent, a), rb = findRoot(parent, b);
      if (ra != rb) parent[static_cast<size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  }
  // Region sizes at the roots, then the runs of small regions invalidated.
  const int runs = static_cast<int>(parent.size());
  std::vector<int>& region = scratch.region_size;
  region.assign(static_cast<size_t>(runs), 0);
  for (int r = 0; r < runs; ++r) region[static_cast<size_t>(findRoot(parent, r))] += length[static_cast<size_t>(r)];
  for (int r = 0; r < runs; ++r) {
    if (region[static_cast<size_t>(findRoot(parent, r))] > window_px) continue;
    const int y = begin[static_cast<size_t>(r)] / cols, x = begin[static_cast<size_t>(r)] % cols;
    const size_t n = static_cast<size_t>(length[static_cast<size_t>(r)]);
    std::fill_n(stripe.ptr<float>(y) + x, n, 0.0f);
    if (confidence) std::fill_n(confidence->ptr<float>(row_begin + y) + x, n, 0.0f);
  }
  // Values that round to 0 in 1/16 px are invalid too (they always were).
  for (int y = 0; y < rows; ++y) {
    const int16_t* f = fixed.ptr<int16_t>(y);
    float* d = stripe.ptr<float>(y);
    float* c = confidence ? confidence->ptr<float>(row_begin + y) : nullptr;
    for (int x = 0; x < cols; ++x) d[x] = f[x] == 0 ? 0.0f : d[x];
    if (c)
      for (int x = 0; x < cols; ++x) c[x] = f[x] == 0 ? 0.0f : c[x];
  }
}

}  // namespace nerv::stereo

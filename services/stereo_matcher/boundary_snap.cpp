#include "boundary_snap.hpp"

#include <cstdlib>
#include <vector>

namespace nerv::stereo {

namespace {

// Disparity of the first valid pixel from x in direction step (within
// `search` pixels), 0 when none.
float nextValid(const float* d, int cols, int x, int step, int search) {
  for (int k = 0; k < search; ++k, x += step) {
    if (x < 0 || x >= cols) return 0.0f;
    if (d[x] > 0.0f) return d[x];
  }
  return 0.0f;
}

// True when pixel x (valid) is a foreground boundary towards direction
// step: the next valid pixel that way is farther by more than jump, or
// there is none (image edge excepted).
bool isBoundary(const float* d, int cols, int x, int step, const BoundarySnapParams& p) {
  const int n = x + step;
  if (n < 0 || n >= cols) return false;
  if (d[n] > 0.0f) return d[x] - d[n] > p.jump_px;
  const float beyond = nextValid(d, cols, n, step, p.hole_search_px);
  return beyond == 0.0f || d[x] - beyond > p.jump_px;
}

}  // namespace

int snapDisparityBoundaries(const cv::Mat& gray, cv::Mat& disparity, cv::Mat& confidence,
                            const BoundarySnapParams& p) {
  CV_Assert(gray.type() == CV_8U && disparity.type() == CV_32F && gray.size() == disparity.size());
  const bool has_conf = !confidence.empty();
  const int cols = disparity.cols;
  int removed = 0;
  std::vector<unsigned char> cut(static_cast<size_t>(cols));
  for (int v = 0; v < disparity.rows; ++v) {
    float* d = disparity.ptr<float>(v);
    const unsigned char* g = gray.ptr<unsigned char>(v);
    std::fill(cut.begin(), cut.end(), 0);
    for (int x = 0; x < cols; ++x) {
      if (!(d[x] > 0.0f)) continue;
      // Right boundary at x: the edge is between e and e+1 for some e in [x - band, x].
      if (isBoundary(d, cols, x, +1, p)) {
        int best = x, best_step = 0;
        for (int e = x; e >= std::max(0, x - p.band_px) && e + 1 < cols; --e) {
          if (!(d[e] > d[x] - p.jump_px)) break;  // left the object (or hit a hole)
          const int s = std::abs(int(g[e + 1]) - int(g[e]));
          if (s > best_step) best_step = s, best = e;
        }
        if (best_step >= p.min_step)
          for (int k = best + 1; k <= x; ++k) cut[k] = 1;
      }
      // Left boundary at x: the edge is between e-1 and e for some e in [x, x + band].
      if (isBoundary(d, cols, x, -1, p)) {
        int best = x, best_step = 0;
        for (int e = x; e <= std::min(cols - 1, x + p.band_px) && e >= 1; ++e) {
          if (!(d[e] > d[x] - p.jump_px)) break;
          const int s = std::abs(int(g[e]) - int(g[e - 1]));
          if (s > best_step) best_step = s, best = e;
        }
        if (best_step >= p.min_step)
          for (int k = x; k < best; ++k) cut[k] = 1;
      }
    }
    float* c = has_conf ? confidence.ptr<float>(v) : nullptr;
    for (int x = 0; x < cols; ++x)
      if (cut[x]) {
        d[x] = 0.0f;
        if (c) c[x] = 0.0f;
        ++removed;
      }
  }
  return removed;
}

}  // namespace nerv::stereo

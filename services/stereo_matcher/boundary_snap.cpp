#include "boundary_snap.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
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

// Where the background begins when pixel x (valid) ends a foreground region
// towards direction step, or -1. Either at once - the next valid pixel is
// farther by more than jump (across at most hole_search invalid pixels, or
// none is found) - or after a short ramp: a matcher that smooths (SGM paths,
// a median) turns the step into a slope of up to `band` mixed pixels, which
// must fall by more than jump between two flat sides (a slanted surface has
// the same slope on both sides and is no boundary).
int backgroundStart(const float* d, int cols, int x, int step, const BoundarySnapParams& p) {
  auto inside = [&](int i) { return i >= 0 && i < cols; };
  const int n = x + step;
  if (!inside(n)) return -1;
  if (!(d[n] > 0.0f)) {
    const float beyond = nextValid(d, cols, n, step, p.hole_search_px);
    return beyond == 0.0f || d[x] - beyond > p.jump_px ? n : -1;
  }
  if (d[x] - d[n] > p.jump_px) return n;
  // Quick reject (most pixels): a ramp ending on flat background has fallen
  // by more than jump at band + 1 pixels too.
  const int far = x + (p.band_px + 1) * step;
  if (!inside(far) || !(d[x] - d[far] > p.jump_px)) return -1;
  for (int m = 2; m <= p.band_px + 1; ++m) {
    const int k = x + m * step, prev = k - step;
    if (!inside(k) || !(d[k] > 0.0f) || d[k] > d[prev] + 0.1f) return -1;  // not a falling ramp
    const float fall = d[x] - d[k];
    if (fall <= p.jump_px) continue;
    const float slope = fall / static_cast<float>(m);
    const int before = x - step, after = k + step;
    const bool flat_before = inside(before) && d[before] > 0.0f && std::abs(d[x] - d[before]) < 0.5f * slope;
    const bool flat_after = inside(after) && d[after] > 0.0f && std::abs(d[k] - d[after]) < 0.5f * slope;
    return flat_before && flat_after ? k : -1;
  }
  return -1;
}

}  // namespace

int snapDisparityBoundaries(const cv::Mat& gray, cv::Mat& disparity, cv::Mat& confidence,
                            const BoundarySnapParams& p) {
  CV_Assert(gray.type() == CV_8U && disparity.type() == CV_32F && gray.size() == disparity.size());
  const bool has_conf = !confidence.empty();
  const int cols = disparity.cols;
  const int reach = p.band_px + 1;
  std::atomic<int> removed{0};
  // Rows are independent: bands of rows on OpenCV's thread pool.
  cv::parallel_for_(cv::Range(0, disparity.rows), [&](const cv::Range& rows) {
    std::vector<unsigned char> cut(static_cast<size_t>(cols)), cand(static_cast<size_t>(cols));
    int local_removed = 0;
    for (int v = rows.start; v < rows.end; ++v) {
      float* d = disparity.ptr<float>(v);
      const unsigned char* g = gray.ptr<unsigned char>(v);
      // Candidates (a branch-free pass the compiler vectorises): valid pixels
      // with a lower or invalid neighbour, or a fall beyond `reach` pixels.
      for (int x = 0; x < cols; ++x) {
        const float dx = d[x];
        const float l1 = x > 0 ? d[x - 1] : dx, r1 = x + 1 < cols ? d[x + 1] : dx;
        const float lr = x >= reach ? d[x - reach] : dx, rr = x + reach < cols ? d[x + reach] : dx;
        const float right = std::min(r1, rr), left = std::min(l1, lr);
        cand[x] = static_cast<unsigned char>(
            (dx > 0.0f) * ((dx - right > p.jump_px || !(right > 0.0f)) * 1 + (dx - left > p.jump_px || !(left > 0.0f)) * 2));
      }
      std::fill(cut.begin(), cut.end(), 0);
      for (int x = 0; x < cols; ++x) {
        if (!cand[x]) continue;
        for (const int step : {+1, -1}) {
          if (!(cand[x] & (step > 0 ? 1 : 2))) continue;
          const int bg = backgroundStart(d, cols, x, step, p);
          if (bg < 0) continue;
          // The object's edge lies between e and e + step, for e from `band`
          // pixels inside x out to the last pixel before the background.
          int best = x, best_step = 0;
          for (int e = bg - step; e != x - reach * step; e -= step) {
            if (e < 0 || e >= cols || e + step < 0 || e + step >= cols) break;
            // From x inwards the object must go on; ramp pixels beyond x may hold the edge.
            if ((e - x) * step <= 0 && !(d[e] > d[x] - p.jump_px)) break;
            const int st = std::abs(int(g[e + step]) - int(g[e]));
            if (st > best_step) best_step = st, best = e;
          }
          if (best_step >= p.min_step)
            for (int k = best + step; k != bg; k += step) cut[k] = 1;
        }
      }
      float* c = has_conf ? confidence.ptr<float>(v) : nullptr;
      for (int x = 0; x < cols; ++x)
        if (cut[x]) {
          d[x] = 0.0f;
          if (c) c[x] = 0.0f;
          ++local_removed;
        }
    }
    removed += local_removed;
  });
  return removed.load();
}

}  // namespace nerv::stereo

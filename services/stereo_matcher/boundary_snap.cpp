#include "boundary_snap.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace nerv::stereo {

namespace {

// Where the background begins when pixel x (valid) ends a foreground region
// towards direction step, or -1. Either at once - the next valid pixel is
// farther by more than jump (across at most hole_search invalid pixels, or
// none is found) - or after a short ramp: a matcher that smooths (SGM paths,
// a median) turns the step into a slope of up to `band` mixed pixels, which
// must fall by more than jump between two flat sides (a slanted surface has
// the same slope on both sides and is no boundary). beyond(): when the
// neighbour is invalid, the disparity of the first valid pixel after it
// within hole_search pixels (0 when none).
template <class Beyond>
int backgroundStart(const float* d, int cols, int x, int step, const BoundarySnapParams& p, Beyond beyond) {
  auto inside = [&](int i) { return i >= 0 && i < cols; };
  const int n = x + step;
  if (!inside(n)) return -1;
  if (!(d[n] > 0.0f)) {
    const float far_side = beyond();
    return far_side == 0.0f || d[x] - far_side > p.jump_px ? n : -1;
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

// Candidate flags of one row (bit 0: may end an object towards +x, bit 1:
// towards -x), a superset of the pixels where backgroundStart can find a
// background, so that the others (most) need not be looked at.
void findCandidates(const float* d, int cols, int reach, float jump, unsigned char* cand) {
  // Near the row ends, and for band 0: valid pixels with a lower or invalid
  // neighbour, or a fall beyond `reach` pixels (a neighbour outside the row
  // counts as the pixel itself).
  auto at_border = [&](int x) {
    const float dx = d[x];
    const float l1 = x > 0 ? d[x - 1] : dx, r1 = x + 1 < cols ? d[x + 1] : dx;
    const float lr = x >= reach ? d[x - reach] : dx, rr = x + reach < cols ? d[x + reach] : dx;
    const float right = std::min(r1, rr), left = std::min(l1, lr);
    return static_cast<unsigned char>(
        (dx > 0.0f) * ((dx - right > jump || !(right > 0.0f)) * 1 + (dx - left > jump || !(left > 0.0f)) * 2));
  };
  const int inner_begin = reach >= 2 ? std::min(reach, cols) : cols;
  const int inner_end = std::max(inner_begin, cols - reach);
  for (int x = 0; x < inner_begin; ++x) cand[x] = at_border(x);
  // The interior: backgroundStart's own first tests - the neighbour is
  // invalid or lower by more than jump, or (its quick reject and the first
  // ramp step) the fall at `reach` pixels exceeds jump and the second pixel
  // is valid and does not rise. No bounds tests, locals the compiler keeps in
  // registers (stores through unsigned char* may alias anything), | rather
  // than ||: vectorised.
  const float* __restrict dr = d;
  unsigned char* __restrict cr = cand;
  for (int x = inner_begin; x < inner_end; ++x) {
    const float dx = dr[x];
    const float r1 = dr[x + 1], r2 = dr[x + 2], rr = dr[x + reach];
    const float l1 = dr[x - 1], l2 = dr[x - 2], lr = dr[x - reach];
    const int towards_right = !(r1 > 0.0f) | (dx - r1 > jump) | ((dx - rr > jump) & (r2 > 0.0f) & !(r2 > r1 + 0.1f));
    const int towards_left = !(l1 > 0.0f) | (dx - l1 > jump) | ((dx - lr > jump) & (l2 > 0.0f) & !(l2 > l1 + 0.1f));
    cr[x] = static_cast<unsigned char>((dx > 0.0f) * (towards_right | towards_left << 1));
  }
  for (int x = inner_end; x < cols; ++x) cand[x] = at_border(x);
}

}  // namespace

int snapDisparityBoundaries(const cv::Mat& gray, cv::Mat& disparity, cv::Mat& confidence,
                            const BoundarySnapParams& p) {
  CV_Assert(gray.type() == CV_8U && disparity.type() == CV_32F && gray.size() == disparity.size());
  const bool has_conf = !confidence.empty();
  const int cols = disparity.cols;
  const int reach = p.band_px + 1;
  const int thin_run = 3 * reach;
  const int hole_search = std::min(p.hole_search_px, cols);  // x + hole_search cannot overflow
  std::atomic<int> removed{0};
  // Rows are independent: bands of rows on OpenCV's thread pool, a few per
  // thread rather than OpenCV's default of one stripe per row (3-5 % faster
  // in an interleaved loop; a row takes a few microseconds).
  const int stripes = std::min(disparity.rows, 4 * std::max(1, cv::getNumThreads()));
  cv::parallel_for_(cv::Range(0, disparity.rows), [&](const cv::Range& rows) {
    // cand is padded to whole words of 8 flags; cut is cleared again where it
    // was set, so it stays zero between rows.
    std::vector<unsigned char> cut(static_cast<size_t>(cols)), cand(static_cast<size_t>(cols) + 8);
    std::vector<int> cuts;  // [begin, end) column ranges set in cut
    int local_removed = 0;
    for (int v = rows.start; v < rows.end; ++v) {
      float* d = disparity.ptr<float>(v);
      const unsigned char* g = gray.ptr<unsigned char>(v);
      findCandidates(d, cols, reach, p.jump_px, cand.data());
      cuts.clear();
      // The object's edge lies between e and e + step, for e from `band`
      // pixels inside x out to the last pixel before the background bg; the
      // pixels from there to bg are marked.
      auto snapBoundary = [&](int x, int step, int bg) {
        // A thin run (a post of a few pixels, fattened on both sides) has both of its
        // sides within the band, and the far one may be the stronger step: cut there,
        // the whole post went. In a run shorter than thin_run pixels, from the pixel
        // before its background to where the disparity leaves d[x] - jump inwards,
        // the edge is looked for on this boundary's half only.
        bool thin = false;
        int mid2 = 0;  // twice the middle of a thin run
        for (int k = 1, opp = x; k <= thin_run; ++k) {
          const int i = x - k * step;
          if (i < 0 || i >= cols || !(d[i] > d[x] - p.jump_px)) {
            thin = true;
            mid2 = bg - step + opp;
            break;
          }
          opp = i;
        }
        int best = x, best_step = 0;
        for (int e = bg - step; e != x - reach * step; e -= step) {
          if (e < 0 || e >= cols || e + step < 0 || e + step >= cols) break;
          // From x inwards the object must go on; ramp pixels beyond x may hold the edge.
          if ((e - x) * step <= 0 && !(d[e] > d[x] - p.jump_px)) break;
          if (thin && (2 * e + step - mid2) * step < 0) break;  // past the middle of a thin run
          const int st = std::abs(int(g[e + step]) - int(g[e]));
          if (st > best_step) best_step = st, best = e;
        }
        if (best_step < p.min_step || best + step == bg) return;
        const int first = best + step, last = bg - step;  // the cut pixels, in either order
        const int lo = std::min(first, last), hi = std::max(first, last) + 1;
        std::memset(&cut[static_cast<size_t>(lo)], 1, static_cast<size_t>(hi - lo));
        cuts.push_back(lo);
        cuts.push_back(hi);
      };
      // Holes are looked across with the flags instead of pixel by pixel:
      // every valid pixel next to an invalid one is a candidate, and invalid
      // pixels are none, so the valid pixel across a hole is the next
      // candidate towards +x, and towards -x the last candidate seen that has
      // an invalid right neighbour.
      int before_hole = -1;
      // The candidates, 8 flags at a time (little-endian: the lowest byte is
      // the leftmost pixel); most words are zero.
      for (int x0 = 0; x0 < cols; x0 += 8) {
        uint64_t word;
        std::memcpy(&word, &cand[static_cast<size_t>(x0)], sizeof word);
        while (word) {
          const int byte = __builtin_ctzll(word) >> 3;
          word &= ~(uint64_t{0xff} << (8 * byte));
          const int x = x0 + byte;
          if (cand[x] & 1) {
            const int bg = backgroundStart(d, cols, x, +1, p, [&] {
              uint64_t rest = word;
              for (int w0 = x0;;) {
                if (rest) {
                  const int next = w0 + (__builtin_ctzll(rest) >> 3);
                  return next <= x + hole_search ? d[next] : 0.0f;
                }
                w0 += 8;
                if (w0 >= cols || w0 > x + hole_search) return 0.0f;
                std::memcpy(&rest, &cand[static_cast<size_t>(w0)], sizeof rest);
              }
            });
            if (bg >= 0) snapBoundary(x, +1, bg);
          }
          if (cand[x] & 2) {
            const int bg = backgroundStart(d, cols, x, -1, p, [&] {
              return before_hole >= 0 && before_hole >= x - hole_search ? d[before_hole] : 0.0f;
            });
            if (bg >= 0) snapBoundary(x, -1, bg);
          }
          if (x + 1 < cols && !(d[x + 1] > 0.0f)) before_hole = x;
        }
      }
      // Applied after the whole row is scanned (the scan reads the pixels it
      // cuts); ranges may overlap, each pixel counts once.
      float* c = has_conf ? confidence.ptr<float>(v) : nullptr;
      for (size_t i = 0; i < cuts.size(); i += 2)
        for (int x = cuts[i]; x < cuts[i + 1]; ++x)
          if (cut[x]) {
            cut[x] = 0;
            d[x] = 0.0f;
            if (c) c[x] = 0.0f;
            ++local_removed;
          }
    }
    removed += local_removed;
  }, stripes);
  return removed.load();
}

}  // namespace nerv::stereo

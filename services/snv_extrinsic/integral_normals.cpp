#include "integral_normals.hpp"

#include <opencv2/imgproc.hpp>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "point_cloud.hpp"

// This file is compiled with -ffp-contract=off (CMakeLists.txt): the vectorised
// row path and the scalar reference must round alike (radius from depth, tests
// "fast == reference").

namespace nerv::snv {

void NormalRow::resize(int n) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  nx.assign(n, nan);
  ny.assign(n, nan);
  nz.assign(n, nan);
  radius.assign(n, 0);
}

namespace {

// Fixed-point scale of the uint32 value integral: SGBM (1/16 px) and KITTI
// ground truth (1/256 px) disparities are exact multiples of 1/256.
constexpr float kFixedScale = 256.0f;

// Running sums along the row: out[0] = 0, out[x+1] = out[x] + in[x]. The
// vertical accumulation follows in accumulateColumns (cv::integral's order).
template <typename In, typename Out>
void rowPrefix(const In* in, int cols, Out* out) {
  Out s = 0;
  out[0] = 0;
  for (int x = 0; x < cols; ++x) {
    s += static_cast<Out>(in[x]);
    out[x + 1] = s;
  }
}

// One row of the integer integrals, edges and (kValues) fixed-point values at
// once: out[x+1] = above[x+1] + in[0] + ... + in[x], out[0] = above[0] (above =
// nullptr: zeros, the first row of a chunk). Wrapping uint32: exact.
template <bool kValues>
void integerIntegralRowsScalar(int cols, const uchar* e, const uint32_t* q, const uint16_t* above_e,
                               const uint32_t* above_q, uint16_t* out_e, uint32_t* out_q) {
  uint32_t se = 0, sq = 0;
  out_e[0] = above_e ? above_e[0] : 0;
  if (kValues) out_q[0] = above_q ? above_q[0] : 0;
  for (int x = 0; x < cols; ++x) {
    se += e[x];
    out_e[x + 1] = static_cast<uint16_t>(se + (above_e ? above_e[x + 1] : 0));
    if (kValues) {
      sq += q[x];
      out_q[x + 1] = sq + (above_q ? above_q[x + 1] : 0);
    }
  }
}

#if defined(__AVX2__)
// The same 8 columns per step: an in-register scan (shift-and-add within each
// 128-bit half, then the lower half's total into the upper one) plus the carry
// of the previous step; the two streams' dependency chains interleave. The
// scalar running sum is sequential (one dependent add per element and stream).
inline __m256i scan8(__m256i x) {
  x = _mm256_add_epi32(x, _mm256_slli_si256(x, 4));
  x = _mm256_add_epi32(x, _mm256_slli_si256(x, 8));
  const __m256i low_total = _mm256_permutevar8x32_epi32(x, _mm256_set1_epi32(3));
  return _mm256_add_epi32(x, _mm256_blend_epi32(_mm256_setzero_si256(), low_total, 0xF0));
}

inline __m256i load8(const uint32_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
inline __m256i load8(const uint16_t* p) {
  return _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
// The low 16 bits of each 32-bit lane, in order (wrapping narrow).
inline void store8(uint16_t* p, __m256i x) {
  const __m256i pick = _mm256_setr_epi8(0, 1, 4, 5, 8, 9, 12, 13, -1, -1, -1, -1, -1, -1, -1, -1,  //
                                        0, 1, 4, 5, 8, 9, 12, 13, -1, -1, -1, -1, -1, -1, -1, -1);
  x = _mm256_permute4x64_epi64(_mm256_shuffle_epi8(x, pick), 0x08);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_castsi256_si128(x));
}

template <bool kValues, bool kAbove>
void integerIntegralRowsAvx2(int cols, const uchar* e, const uint32_t* q, const uint16_t* above_e,
                             const uint32_t* above_q, uint16_t* out_e, uint32_t* out_q) {
  __m256i carry_e = _mm256_setzero_si256(), carry_q = _mm256_setzero_si256();
  const __m256i last = _mm256_set1_epi32(7);
  int x = 0;
  for (; x + 8 <= cols; x += 8) {
    const __m256i ev = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(e + x)));
    const __m256i se = _mm256_add_epi32(scan8(ev), carry_e);
    carry_e = _mm256_permutevar8x32_epi32(se, last);
    store8(out_e + x + 1, kAbove ? _mm256_add_epi32(se, load8(above_e + x + 1)) : se);
    if (kValues) {
      const __m256i sq = _mm256_add_epi32(scan8(load8(q + x)), carry_q);
      carry_q = _mm256_permutevar8x32_epi32(sq, last);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out_q + x + 1),
                          kAbove ? _mm256_add_epi32(sq, load8(above_q + x + 1)) : sq);
    }
  }
  out_e[0] = kAbove ? above_e[0] : 0;
  if (kValues) out_q[0] = kAbove ? above_q[0] : 0;
  uint32_t se = static_cast<uint32_t>(_mm256_cvtsi256_si32(carry_e));
  uint32_t sq = static_cast<uint32_t>(_mm256_cvtsi256_si32(carry_q));
  for (; x < cols; ++x) {
    se += e[x];
    out_e[x + 1] = static_cast<uint16_t>(se + (kAbove ? above_e[x + 1] : 0));
    if (kValues) {
      sq += q[x];
      out_q[x + 1] = sq + (kAbove ? above_q[x + 1] : 0);
    }
  }
}
#endif

template <bool kValues>
void integerIntegralRows(int cols, const uchar* e, const uint32_t* q, const uint16_t* above_e,
                         const uint32_t* above_q, uint16_t* out_e, uint32_t* out_q) {
#if defined(__AVX2__)
  if (above_e)
    integerIntegralRowsAvx2<kValues, true>(cols, e, q, above_e, above_q, out_e, out_q);
  else
    integerIntegralRowsAvx2<kValues, false>(cols, e, q, above_e, above_q, out_e, out_q);
#else
  integerIntegralRowsScalar<kValues>(cols, e, q, above_e, above_q, out_e, out_q);
#endif
}

// integral[y][x] += integral[y-1][x] over all rows, columns in parallel blocks
// (each column is independent; rows of one block are contiguous vector adds).
template <typename T>
void accumulateColumns(cv::Mat& integral) {
  const int cols = integral.cols, block = 512;
  cv::parallel_for_(cv::Range(0, (cols + block - 1) / block), [&](const cv::Range& range) {
    const int x0 = range.start * block, x1 = std::min(cols, range.end * block);
    for (int y = 1; y < integral.rows; ++y) {
      const T* prev = integral.ptr<T>(y - 1);
      T* cur = integral.ptr<T>(y);
      for (int x = x0; x < x1; ++x) cur[x] += prev[x];
    }
  });
}

// First band row of chunk c when `rows` rows are cut into `chunks` chunks.
inline int chunkBegin(int rows, int chunks, int c) { return static_cast<int>(int64_t(rows) * c / chunks); }

// to[x] += from[x] (wrapping; vectorised).
template <typename T>
inline void addRow(const T* from, T* to, int n) {
  for (int x = 0; x < n; ++x) to[x] = static_cast<T>(to[x] + from[x]);
}

// Integral rows accumulated within chunks (see prepare()): add to every row of
// chunk c the final last row of chunk c - 1, chunk after chunk, columns in
// parallel blocks.
template <typename T>
void addChunkOffsets(cv::Mat& integral, int rows, int chunks) {
  const int cols = integral.cols, block = 512;
  for (int c = 1; c < chunks; ++c) {
    const int y_end = chunkBegin(rows, chunks, c + 1);
    const T* offset = integral.ptr<T>(chunkBegin(rows, chunks, c));  // integral row = last row of c - 1
    cv::parallel_for_(cv::Range(0, (cols + block - 1) / block), [&](const cv::Range& range) {
      const int x0 = range.start * block, x1 = std::min(cols, range.end * block);
      for (int y = chunkBegin(rows, chunks, c) + 1; y <= y_end; ++y) addRow(offset + x0, integral.ptr<T>(y) + x0, x1 - x0);
    });
  }
}

// A continuous rows x cols matrix in `buffer`, which grows to the largest
// region seen (at least `min_bytes`): a field kept across frames then allocates
// - and page-faults - its ~3 MB once instead of every frame (0.3-0.9 ms of page
// faults per frame measured when freed memory went back to the system between
// frames), whatever the size of each frame's region.
cv::Mat bufferView(cv::Mat& buffer, int rows, int cols, int type, size_t min_bytes) {
  const size_t bytes = size_t(rows) * cols * CV_ELEM_SIZE(type);
  if (buffer.empty() || buffer.total() < bytes) buffer.create(1, static_cast<int>(std::max(bytes, min_bytes)), CV_8U);
  return cv::Mat(rows, cols, type, buffer.data);
}

// Box sum from four integral rows/columns, as float.
inline float boxFloat(const uint32_t* a, const uint32_t* b, int x0, int x1) {
  return static_cast<float>(static_cast<int32_t>(b[x1] - a[x1] - b[x0] + a[x0]));
}
inline float boxFloat(const double* a, const double* b, int x0, int x1) {
  return static_cast<float>(b[x1] - a[x1] - b[x0] + a[x0]);
}

}  // namespace

void IntegralNormalField::prepare(const cv::Mat& disparity, const StereoCamera& cam,
                                  const IntegralNormalParams& params, int row_begin, int row_end) {
  const int r0 = std::clamp(row_begin, 0, disparity.rows);
  const int r1 = std::clamp(row_end, r0, disparity.rows);
  prepare(disparity, cam, params, cv::Rect(0, r0, disparity.cols, r1 - r0));
}

void IntegralNormalField::prepare(const cv::Mat& disparity, const StereoCamera& cam,
                                  const IntegralNormalParams& params, const cv::Rect& region) {
  CV_Assert(disparity.type() == CV_32F);
  disparity_ = disparity;
  cam_ = cam;
  params_ = params;
  const cv::Rect r = region & cv::Rect(0, 0, disparity.cols, disparity.rows);
  row0_ = r.empty() ? 0 : r.y;
  row1_ = r.empty() ? 0 : r.y + r.height;
  col0_ = r.empty() ? 0 : r.x;
  col1_ = r.empty() ? 0 : r.x + r.width;
  fb_ = static_cast<float>(cam.fx * cam.baseline_m);
  inv_fx_ = static_cast<float>(1.0 / cam.fx);
  inv_fy_ = static_cast<float>(1.0 / cam.fy);

  const int rows = row1_ - row0_, cols = col1_ - col0_;
  // Storage for the whole image at least, so a full frame after smaller regions reuses it.
  const size_t image_px = size_t(disparity.rows + 1) * (disparity.cols + 1);
  edge_integral_ = bufferView(edge_integral_buffer_, rows + 1, cols + 1, CV_16U, image_px * 2);
  edge_integral_.row(0).setTo(0);
  // Fixed point is tried first (one pass); an inexact value falls back to CV_64F.
  bool fixed = params.smooth_disparity;
  value_integral_ = fixed ? bufferView(fixed_buffer_, rows + 1, cols + 1, CV_32S, image_px * 4)
                          : bufferView(double_buffer_, rows + 1, cols + 1, CV_64F, image_px * 8);
  value_integral_.row(0).setTo(0);
  if (rows == 0 || cols == 0) {
    fixed_point_ = fixed;
    return;
  }
  std::atomic<bool> inexact{false};

  // Edge map, values and their row prefix sums in chunks of consecutive rows,
  // one per thread. Integer integrals are accumulated down the chunk while the
  // previous row is still in cache (a separate column pass re-read and re-wrote
  // ~2 MB per frame); each chunk's offset, the last row of the one above, is
  // added afterwards (wrapping integers: exact, same sums). The CV_64F integral
  // keeps the separate column pass (cv::integral's summation order).
  const int chunks = std::clamp(cv::getNumThreads(), 1, std::max(1, rows / 16));
  cv::parallel_for_(cv::Range(0, chunks), [&](const cv::Range& range) {
    // Locals, not captures: a uchar store could alias a captured value and
    // keep the loops below from vectorising.
    const int cols = col1_ - col0_;
    const bool right_edge = col1_ == disparity.cols;  // the region's last column is the image's
    const float jump_px = params.depth_change_px, jump_rel = params.depth_change_rel;
    const bool smooth = params.smooth_disparity;
    const float fb = fb_;
    std::vector<float> value(cols);
    std::vector<uint32_t> fixed_value(cols);
    std::vector<uchar> edge(cols);  // the edge map lives only in its integral
    for (int chunk = range.start; chunk < range.end; ++chunk)
      for (int y = chunkBegin(rows, chunks, chunk), y_end = chunkBegin(rows, chunks, chunk + 1); y < y_end; ++y) {
        const bool accumulate = y > chunkBegin(rows, chunks, chunk);
        const int v = y + row0_;
        const float* d = disparity.ptr<float>(v) + col0_;  // region columns from here on
        const float* below = (v + 1 < disparity.rows ? disparity.ptr<float>(v + 1) : disparity.ptr<float>(v)) + col0_;
        uchar* e = edge.data();
        float* val = value.data();
        // Branch-free so it vectorises. A jump to the right or below marks this
        // pixel: any window spanning the jump contains it.
        auto pixel = [&](int u, float right) {
          const float c = d[u];
          const bool valid = (c > 0.0f) & (c < 1e6f);  // validDisparity
          const float safe = valid ? c : 1.0f;
          const float depth = fb / safe;
          const float thr = std::max(jump_px, jump_rel * c);
          const bool jump = (std::abs(right - c) > thr) | (std::abs(below[u] - c) > thr);
          e[u] = static_cast<uchar>(!valid | jump);
          val[u] = valid ? (smooth ? c : depth) : 0.0f;
        };
        for (int u = 0; u + 1 < cols; ++u) pixel(u, d[u + 1]);
        pixel(cols - 1, right_edge ? d[cols - 1] : d[cols]);  // the image's edge map, also at the region's side
        uint16_t* edge_row = edge_integral_.ptr<uint16_t>(y + 1);
        const uint16_t* edge_above = accumulate ? edge_integral_.ptr<uint16_t>(y) : nullptr;
        if (fixed) {
          int bad = 0;
          uint32_t* q = fixed_value.data();
          for (int u = 0; u < cols; ++u) {
            const float scaled = val[u] * kFixedScale;
            const float rounded = std::nearbyint(scaled);
            bad |= rounded != scaled;
            q[u] = static_cast<uint32_t>(static_cast<int32_t>(rounded));
          }
          if (bad) inexact = true;  // the value rows are redone in CV_64F below
          integerIntegralRows<true>(cols, e, q, edge_above,
                                    accumulate ? value_integral_.ptr<uint32_t>(y) : nullptr, edge_row,
                                    value_integral_.ptr<uint32_t>(y + 1));
        } else {
          integerIntegralRows<false>(cols, e, nullptr, edge_above, nullptr, edge_row, nullptr);
          rowPrefix(val, cols, value_integral_.ptr<double>(y + 1));
        }
      }
  });
  if (fixed && inexact) {
    // Not a multiple of 1/256 somewhere: exact sums need the CV_64F integral.
    fixed = false;
    value_integral_ = bufferView(double_buffer_, rows + 1, cols + 1, CV_64F, image_px * 8);
    value_integral_.row(0).setTo(0);
    cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
      std::vector<float> value(cols);
      for (int y = range.start; y < range.end; ++y) {
        const float* d = disparity.ptr<float>(y + row0_) + col0_;
        for (int u = 0; u < cols; ++u) value[u] = validDisparity(d[u]) ? d[u] : 0.0f;
        rowPrefix(value.data(), cols, value_integral_.ptr<double>(y + 1));
      }
    });
  }
  fixed_point_ = fixed;
  addChunkOffsets<uint16_t>(edge_integral_, rows, chunks);
  if (fixed_point_)
    addChunkOffsets<uint32_t>(value_integral_, rows, chunks);
  else
    accumulateColumns<double>(value_integral_);
}

void IntegralNormalField::normalRow(int v, int u0, int count, int step, NormalRow& out) const {
  const bool inside = count > 0 && !empty() && v >= row0_ && v < row1_;
  if (!inside || std::min(params_.max_radius_px, std::min(v - row0_, row1_ - 1 - v) / 2) < 1) {
    out.resize(std::max(count, 0));  // no sample has a normal
    return;
  }
  CV_Assert(step >= 1 && u0 >= col0_ && u0 + (count - 1) * step < col1_);
  // Every sample is written below: sized, not filled.
  out.nx.resize(count);
  out.ny.resize(count);
  out.nz.resize(count);
  out.radius.resize(count);
  // A compile-time unit step gives contiguous vector loads (a run-time step, strided ones).
  if (step == 1)
    normalRowImpl<true>(v, u0, count, 1, out);
  else
    normalRowImpl<false>(v, u0, count, step, out);
}

template <bool kUnit>
void IntegralNormalField::normalRowImpl(int v, int u0, int count, int run_step, NormalRow& out) const {
  const int step = kUnit ? 1 : run_step;
  const int c0 = col0_, c1 = col1_;  // integral column x holds image column u = x + c0
  const int vb = std::min(v - row0_, row1_ - 1 - v);
  const int rmax = std::min(params_.max_radius_px, vb / 2);  // >= 1 (normalRow)

  // 1. Radius from depth and borders (depthRadius), branch-free. Radii are
  //    int16 here: with the uint16 edge integral, twice the lanes per vector.
  const float* d = disparity_.ptr<float>(v);
  thread_local std::vector<int16_t> radius_buffer, depth_buffer;
  radius_buffer.resize(count);
  depth_buffer.resize(count);
  int16_t* rad = radius_buffer.data();
  int16_t* rt = depth_buffer.data();
  const float base = params_.window_base_px, per_m = params_.window_px_per_m;
  const float cap = static_cast<float>(params_.max_radius_px);
  for (int i = 0; i < count; ++i) {
    const int u = u0 + i * step;
    const float c = d[u];
    const bool valid = (c > 0.0f) & (c < 1e6f);
    const float z = fb_ / (valid ? c : 1.0f);
    // min() in float first: same integer as the reference, without an out-of-range conversion.
    const int r = static_cast<int>(std::min((base + per_m * z) * 0.5f, cap));
    const int border = std::min(std::min(u - c0, c1 - 1 - u), vb);
    rt[i] = static_cast<int16_t>(valid ? std::max(0, std::min(r, border / 2)) : 0);
    rad[i] = 0;
  }
  // 2. Adaptive radius: the largest r <= rt whose (4r+1)^2 window holds no edge
  //    (windows are nested, so this equals the reference's shrinking loop).
  //    Edge counts wrap modulo 2^16: exact, a window holds at most 253^2 pixels.
  if (kUnit) {
    // Grow r = 1, 2, ... over the whole row: contiguous loads, vectorised.
    for (int r = 1; r <= rmax; ++r) {
      const int w = 2 * r;
      const uint16_t* a = edge_integral_.ptr<uint16_t>(v - w - row0_);
      const uint16_t* b = edge_integral_.ptr<uint16_t>(v + w + 1 - row0_);
      // Only pixels whose windows fit in the columns can have rt >= r.
      const int i_lo = std::max(0, c0 + w - u0);
      const int i_hi = std::min(count, std::max(0, c1 - w - u0));
      const int16_t r16 = static_cast<int16_t>(r), below = static_cast<int16_t>(r - 1);
      int16_t grown = 0;
      for (int i = i_lo; i < i_hi; ++i) {
        const int u = u0 + i - c0;
        const uint16_t edges = static_cast<uint16_t>(b[u + w + 1] - a[u + w + 1] - b[u - w] + a[u - w]);
        const int16_t ok = (edges == 0) & (rad[i] == below) & (rt[i] >= r16);
        rad[i] = static_cast<int16_t>(rad[i] + ok);
        grown |= ok;
      }
      if (!grown) break;
    }
  } else {
    // Strided: every load is a gather, so shrink from rt per pixel instead
    // (one window test on clear surfaces, rather than one per radius).
    constexpr int kMaxRadius = 63;
    CV_Assert(rmax <= kMaxRadius);
    const uint16_t* a_row[kMaxRadius + 1];
    const uint16_t* b_row[kMaxRadius + 1];
    for (int r = 1; r <= rmax; ++r) {
      a_row[r] = edge_integral_.ptr<uint16_t>(v - 2 * r - row0_);
      b_row[r] = edge_integral_.ptr<uint16_t>(v + 2 * r + 1 - row0_);
    }
    for (int i = 0; i < count; ++i) {
      const int u = u0 + i * step - c0;
      int r = rt[i];
      for (; r >= 1; --r) {
        const int w = 2 * r;
        const uint16_t* a = a_row[r];
        const uint16_t* b = b_row[r];
        if (static_cast<uint16_t>(b[u + w + 1] - a[u + w + 1] - b[u - w] + a[u - w]) == 0) break;
      }
      rad[i] = static_cast<int16_t>(r);
    }
  }
  int* out_radius = out.radius.data();
  for (int i = 0; i < count; ++i) out_radius[i] = rad[i];
  // 3. Normals over runs of equal radius (long on roads and walls).
  if (fixed_point_)
    normalRuns<uint32_t, kUnit>(v, u0, count, step, out);
  else
    normalRuns<double, kUnit>(v, u0, count, step, out);
}

namespace {

// The value-integral rows and constants of one radius r at grid row v, and the
// normal of column u from its four box sums (the fast path's kernel; the
// reference is IntegralNormalField::normalAt).
template <typename Acc>
struct RadiusBoxes {
  const Acc *a, *b, *zd0, *zd1, *zu0, *zu1;
  int r, right0, left0, side;
  float yd, yu, yc;

  // Box rows: left/right centres (v-r .. v+r), down (v .. v+2r), up (v-2r .. v).
  // Z ~ 1/S (disparity smoothed) or Z ~ S (depth smoothed). N's direction does not
  // change when h is scaled by S_r*S_l > 0 and t by S_d*S_u > 0, so with smoothed
  // disparity z_r -> S_l, z_l -> S_r (and likewise d/u): no division per pixel.
  template <typename RowOf>
  RadiusBoxes(RowOf row, int v, int radius, bool smooth, float cy, float ify) : r(radius) {
    a = row(v - r);
    b = row(v + r + 1);
    const Acc* dn0 = row(v);
    const Acc* dn1 = row(v + 2 * r + 1);
    const Acc* up0 = row(v - 2 * r);
    const Acc* up1 = row(v + 1);
    zd0 = smooth ? up0 : dn0;
    zd1 = smooth ? up1 : dn1;
    zu0 = smooth ? dn0 : up0;
    zu1 = smooth ? dn1 : up1;
    right0 = smooth ? -2 * r : 0;  // box column starts
    left0 = smooth ? 0 : -2 * r;
    side = 2 * r + 1;
    yd = (v + r - cy) * ify;
    yu = (v - r - cy) * ify;
    yc = (v - cy) * ify;
  }

  // Unit normal at image column u, integral column x (NaN when a smoothed depth
  // is not positive).
  inline __attribute__((always_inline)) void normal(int u, int x, float cx, float ifx, float& nxo,
                                                    float& nyo, float& nzo) const {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float zr = boxFloat(a, b, x + right0, x + right0 + side);
    const float zl = boxFloat(a, b, x + left0, x + left0 + side);
    const float zd = boxFloat(zd0, zd1, x - r, x + r + 1);
    const float zu = boxFloat(zu0, zu1, x - r, x + r + 1);
    const float uf = static_cast<float>(u);
    const float xr = (uf + r - cx) * ifx, xl = (uf - r - cx) * ifx, xc = (uf - cx) * ifx;
    const float hx = xr * zr - xl * zl, hy = yc * (zr - zl), hz = zr - zl;
    const float tx = xc * (zd - zu), ty = yd * zd - yu * zu, tz = zd - zu;
    const float nx = ty * hz - tz * hy, ny = tz * hx - tx * hz, nz = tx * hy - ty * hx;
    const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
    const bool ok = (zr > 0) & (zl > 0) & (zd > 0) & (zu > 0) & (len > 0);
    const float inv = 1.0f / (ok ? len : 1.0f);
    nxo = ok ? nx * inv : nan;
    nyo = ok ? ny * inv : nan;
    nzo = ok ? nz * inv : nan;
  }
};

}  // namespace

template <typename Acc, bool kUnit>
void IntegralNormalField::normalRuns(int v, int u0, int count, int run_step, NormalRow& out) const {
  const int step = kUnit ? 1 : run_step;
  const int* rad = out.radius.data();
  float* nxo = out.nx.data();
  float* nyo = out.ny.data();
  float* nzo = out.nz.data();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float cx = static_cast<float>(cam_.cx), cy = static_cast<float>(cam_.cy);
  const float ifx = inv_fx_, ify = inv_fy_;
  const bool smooth = params_.smooth_disparity;
  auto row = [&](int image_row) { return value_integral_.ptr<Acc>(image_row - row0_); };
  if (!kUnit) {
    // Strided samples: every load is a gather either way; runs of equal radius
    // (long on roads and walls) compute each sample once.
    for (int i = 0; i < count;) {
      const int r = rad[i];
      int j = i + 1;
      while (j < count && rad[j] == r) ++j;
      if (r < 1) {
        for (int k = i; k < j; ++k) nxo[k] = nyo[k] = nzo[k] = nan;
      } else {
        const RadiusBoxes<Acc> boxes(row, v, r, smooth, cy, ify);
        for (int k = i; k < j; ++k) {
          const int u = u0 + k * step;
          boxes.normal(u, u - col0_, cx, ifx, nxo[k], nyo[k], nzo[k]);
        }
      }
      i = j;
    }
    return;
  }
  // Unit step: blocks of kBlock samples, one full-width vector pass per radius
  // present in the block (one or two on roads and walls, a few near edges),
  // contiguous loads. Runs of equal radius left short runs to scalar loop
  // tails: on stereo disparity with its holes most runs are short (map at
  // interval 1: 3.3 -> 2.0 ms with the uint16 edge integral, bench_snv).
  constexpr int kBlock = 16;
  for (int b0 = 0; b0 < count; b0 += kBlock) {
    const int n = std::min(kBlock, count - b0);
    uint32_t present = 0;  // bit r: some sample of the block has radius r (r <= 31)
    for (int k = 0; k < n; ++k) present |= 1u << std::min(rad[b0 + k], 31);
    present &= ~1u;  // radius 0: no normal
    float bx[kBlock], by[kBlock], bz[kBlock];
    for (int k = 0; k < kBlock; ++k) bx[k] = by[k] = bz[k] = nan;
    while (present) {
      const int r = __builtin_ctz(present);
      present &= present - 1;
      const RadiusBoxes<Acc> boxes(row, v, r, smooth, cy, ify);
      // Samples of another radius may sit where this radius' windows leave the
      // image: in a block at the border their columns are clamped (the value is
      // discarded by the select). Inner blocks load contiguously.
      auto pass = [&](auto clamp_tag, auto full_tag) {
        constexpr bool kClamp = decltype(clamp_tag)::value;
        constexpr bool kFull = decltype(full_tag)::value;
        const int lo = col0_ + 2 * r, hi = col1_ - 1 - 2 * r;
        const int m = kFull ? kBlock : n;
        // A local copy: the stores to bx/by/bz below could alias the float
        // members of `boxes` (address-taken) and force a reload per iteration.
        const RadiusBoxes<Acc> local = boxes;
        for (int k = 0; k < m; ++k) {
          const int u = kClamp ? std::min(std::max(u0 + b0 + k, lo), hi) : u0 + b0 + k;
          float x, y, z;
          local.normal(u, u - col0_, cx, ifx, x, y, z);
          const bool mine = rad[b0 + k] == r;
          bx[k] = mine ? x : bx[k];
          by[k] = mine ? y : by[k];
          bz[k] = mine ? z : bz[k];
        }
      };
      const bool inside = u0 + b0 >= col0_ + 2 * r && u0 + b0 + n - 1 <= col1_ - 1 - 2 * r;
      using Yes = std::true_type;
      using No = std::false_type;
      if (!inside)
        pass(Yes{}, No{});
      else if (n == kBlock)
        pass(No{}, Yes{});
      else
        pass(No{}, No{});
    }
    for (int k = 0; k < n; ++k) {
      nxo[b0 + k] = bx[k];
      nyo[b0 + k] = by[k];
      nzo[b0 + k] = bz[k];
    }
  }
}

double IntegralNormalField::boxSum(int u, int v, int r) const {
  const int y0 = v - r - row0_, y1 = v + r + 1 - row0_, x0 = u - r - col0_, x1 = u + r + 1 - col0_;
  if (fixed_point_) {
    const uint32_t* a = value_integral_.ptr<uint32_t>(y0);
    const uint32_t* b = value_integral_.ptr<uint32_t>(y1);
    const int32_t s = static_cast<int32_t>(b[x1] - a[x1] - b[x0] + a[x0]);  // exact modulo 2^32
    return s / static_cast<double>(kFixedScale);
  }
  const double* a = value_integral_.ptr<double>(y0);
  const double* b = value_integral_.ptr<double>(y1);
  return b[x1] - a[x1] - b[x0] + a[x0];
}

int IntegralNormalField::edgeCount(int u, int v, int r) const {
  const int y0 = v - r - row0_, y1 = v + r + 1 - row0_, x0 = u - r - col0_, x1 = u + r + 1 - col0_;
  const uint16_t* a = edge_integral_.ptr<uint16_t>(y0);
  const uint16_t* b = edge_integral_.ptr<uint16_t>(y1);
  return static_cast<uint16_t>(b[x1] - a[x1] - b[x0] + a[x0]);  // exact: (2r+1)^2 < 2^16
}

float IntegralNormalField::smoothedDepth(int u, int v, int r) const {
  const double side = 2 * r + 1;
  const double mean = boxSum(u, v, r) / (side * side);
  if (params_.smooth_disparity) return mean > 0 ? static_cast<float>(fb_ / mean) : -1.0f;
  return static_cast<float>(mean);
}

int IntegralNormalField::depthRadius(int u, int v) const {
  if (u < col0_ || u >= col1_ || v < row0_ || v >= row1_) return 0;
  const float d = disparity_.at<float>(v, u);
  if (!validDisparity(d)) return 0;
  const float z = fb_ / d;
  int r = static_cast<int>((params_.window_base_px + params_.window_px_per_m * z) * 0.5f);
  r = std::min(r, params_.max_radius_px);
  // Every smoothing window reaches 2r from the centre and must stay in the region.
  const int border = std::min({u - col0_, col1_ - 1 - u, v - row0_, row1_ - 1 - v});
  return std::max(0, std::min(r, border / 2));
}

int IntegralNormalField::adaptiveRadius(int u, int v) const {
  int r = depthRadius(u, v);
  while (r >= 1 && edgeCount(u, v, 2 * r) > 0) --r;
  return r;
}

bool IntegralNormalField::normalAt(int u, int v, int r, cv::Vec3f& n) const {
  const float zr = smoothedDepth(u + r, v, r), zl = smoothedDepth(u - r, v, r);
  const float zd = smoothedDepth(u, v + r, r), zu = smoothedDepth(u, v - r, r);
  if (!(zr > 0 && zl > 0 && zd > 0 && zu > 0)) return false;
  const float cx = static_cast<float>(cam_.cx), cy = static_cast<float>(cam_.cy);
  const float xr = (u + r - cx) * inv_fx_, xl = (u - r - cx) * inv_fx_, xc = (u - cx) * inv_fx_;
  const float yd = (v + r - cy) * inv_fy_, yu = (v - r - cy) * inv_fy_, yc = (v - cy) * inv_fy_;
  // Horizontal tangent h and vertical tangent t between the smoothed points.
  const float hx = xr * zr - xl * zl, hy = yc * (zr - zl), hz = zr - zl;
  const float tx = xc * (zd - zu), ty = yd * zd - yu * zu, tz = zd - zu;
  // N = t x h faces the camera for any visible surface.
  const float nx = ty * hz - tz * hy, ny = tz * hx - tx * hz, nz = tx * hy - ty * hx;
  const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (!(len > 0)) return false;
  const float inv = 1.0f / len;
  n = cv::Vec3f(nx * inv, ny * inv, nz * inv);
  return true;
}

cv::Mat IntegralNormalField::edgeDistance() const {
  // The edge map, recovered from its integral (1 x 1 boxes).
  const int rows = edge_integral_.rows - 1, cols = edge_integral_.cols - 1;
  cv::Mat inside(rows, cols, CV_8U);  // 255 off edges
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x)
      inside.at<uchar>(y, x) = edgeCount(x + col0_, y + row0_, 0) == 0 ? 255 : 0;
  cv::Mat dist;
  cv::distanceTransform(inside, dist, cv::DIST_C, 3, CV_32F);
  return dist;
}

NormalMap computeNormalMap(const cv::Mat& disparity, const StereoCamera& cam,
                           const IntegralNormalParams& params, int interval_px) {
  CV_Assert(interval_px >= 1);
  NormalMap map;
  map.interval_px = interval_px;
  const int gw = (disparity.cols + interval_px - 1) / interval_px;
  const int gh = (disparity.rows + interval_px - 1) / interval_px;
  map.normals.create(gh, gw, CV_32FC3);
  if (disparity.empty()) return map;

  // One field per calling thread, kept: its buffers are reused by the next map.
  // (Bound to a local reference: inside the parallel lambda the name of a
  // thread_local would mean the worker thread's own, empty, instance.)
  thread_local IntegralNormalField kept;
  IntegralNormalField& field = kept;
  field.prepare(disparity, cam, params);
  // r = min(B, T) read from the edge integral rather than a cv::distanceTransform:
  // the same radius (see edgeDistance() and its test) without a full-frame transform.
  cv::parallel_for_(cv::Range(0, gh), [&](const cv::Range& range) {
    NormalRow row;
    for (int j = range.start; j < range.end; ++j) {
      field.normalRow(j * interval_px, 0, gw, interval_px, row);
      cv::Vec3f* out = map.normals.ptr<cv::Vec3f>(j);
      // Interleaved by cv::merge (vector stores; a per-pixel Vec3f copy was 5 % of the map).
      const cv::Mat planes[3] = {cv::Mat(1, gw, CV_32F, row.nx.data()), cv::Mat(1, gw, CV_32F, row.ny.data()),
                                 cv::Mat(1, gw, CV_32F, row.nz.data())};
      cv::Mat dst(1, gw, CV_32FC3, out);
      cv::merge(planes, 3, dst);
    }
  });
  return map;
}

}  // namespace nerv::snv

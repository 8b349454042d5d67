#include "gated_mean.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace nerv::stereo {

namespace {
// Pixels a step of the vector loop: GCC's vector types, which it compiles to AVX2 (8 floats),
// SSE (4) or NEON (4) alike.
#ifdef __AVX2__
constexpr int kLanes = 8;
#else
constexpr int kLanes = 4;
#endif
typedef float Floats __attribute__((vector_size(4 * kLanes)));
typedef int32_t Lanes __attribute__((vector_size(4 * kLanes)));

inline Floats loadFloats(const float* p) {
  Floats v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
}  // namespace

void gatedMeanRows(const cv::Mat& before, cv::Mat& disparity, const GatedMeanParams& p, int row_begin,
                   int row_end) {
  CV_Assert(before.type() == CV_32FC1 && disparity.type() == CV_32FC1 && before.size() == disparity.size() &&
            before.data != disparity.data);
  const int rows = disparity.rows, cols = disparity.cols, r = p.radius;
  row_begin = std::max(row_begin, 0);
  row_end = std::min(row_end, rows);
  if (r <= 0 || row_begin >= row_end) return;
  std::vector<const float*> window;
  for (int y = row_begin; y < row_end; ++y) {
    const float* c = before.ptr<float>(y);
    float* out = disparity.ptr<float>(y);
    window.clear();
    for (int yy = std::max(0, y - r); yy <= std::min(rows - 1, y + r); ++yy) window.push_back(before.ptr<float>(yy));
    // One pixel; the neighbours are summed in the order (row, column) of the
    // SIMD lanes below, so both give the same floats.
    auto pixel = [&](int x) {
      if (!(c[x] > 0.0f)) return;
      const float gate = std::max(p.range_px, p.range_rel * c[x]);
      float sum = 0.0f, count = 0.0f;
      for (const float* w : window)
        for (int xx = std::max(0, x - r); xx <= std::min(cols - 1, x + r); ++xx)
          if (w[xx] > 0.0f && std::fabs(w[xx] - c[x]) <= gate) {
            sum += w[xx];
            count += 1.0f;
          }
      out[x] = sum / count;  // the pixel itself is always in
    };
    int x = 0;
    for (; x < std::min(r, cols); ++x) pixel(x);
    // kLanes pixels at a time where the whole window lies inside the row; the sums stay in
    // registers over the window, added in the scalar pixel's order (the same floats).
    const Floats zero = Floats{}, one = zero + 1.0f;
    for (; x + kLanes <= cols - r; x += kLanes) {
      const Floats cv = loadFloats(c + x);
      const Floats scaled = p.range_rel * cv;
      const Floats gate = scaled > p.range_px ? scaled : zero + p.range_px;
      Floats sum = zero, count = zero;
      for (const float* w : window)
        for (int dx = -r; dx <= r; ++dx) {
          const Floats q = loadFloats(w + x + dx);
          const Floats distance = (Floats)((Lanes)(q - cv) & 0x7fffffff);  // |q - c|: the sign bit off
          const Lanes in = (q > 0.0f) & (distance <= gate);                 // all ones or zero
          sum += (Floats)(in & (Lanes)q);
          count += (Floats)(in & (Lanes)one);
        }
      const Floats mean = cv > 0.0f ? sum / count : cv;
      std::memcpy(out + x, &mean, sizeof mean);
    }
    for (; x < cols; ++x) pixel(x);
  }
}

}  // namespace nerv::stereo

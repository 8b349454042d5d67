#include "plane_resampler.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace nerv::stereo {

namespace {

double lanczos(double d) {
  constexpr double a = PlaneResampler::kTaps / 2;
  if (d == 0) return 1;
  if (std::abs(d) >= a) return 0;
  const double p = CV_PI * d;
  return a * std::sin(p) * std::sin(p / a) / (p * p);
}

using Table = std::array<std::array<int16_t, PlaneResampler::kTaps>, PlaneResampler::kSteps>;

Table makeTable() {
  Table t{};
  constexpr int one = 1 << PlaneResampler::kShift;
  for (int q = 0; q < PlaneResampler::kSteps; ++q) {
    const double f = static_cast<double>(q) / PlaneResampler::kSteps;
    std::array<double, PlaneResampler::kTaps> w{};
    double sum = 0;
    for (int k = 0; k < PlaneResampler::kTaps; ++k) sum += w[k] = lanczos(k - 3 - f);
    int total = 0;
    for (int k = 0; k < PlaneResampler::kTaps; ++k) total += t[q][k] = static_cast<int16_t>(std::lround(one * w[k] / sum));
    t[q][f < 0.5 ? 3 : 4] += static_cast<int16_t>(one - total);  // the rounding onto the nearest tap: sums to one
  }
  return t;
}

// p as floor and fraction in 1 / kSteps.
void split(double p, int& base, int& step) {
  base = static_cast<int>(std::floor(p));
  step = static_cast<int>(std::lround((p - base) * PlaneResampler::kSteps));
  if (step == PlaneResampler::kSteps) {
    ++base;
    step = 0;
  }
}

uint8_t saturate(int32_t sum) {
  const int32_t v = (sum + (1 << (PlaneResampler::kShift - 1))) >> PlaneResampler::kShift;
  return static_cast<uint8_t>(std::clamp(v, 0, 255));
}

}  // namespace

const int16_t* PlaneResampler::weights(int q) {
  static const Table table = makeTable();
  return table[q].data();
}

void PlaneResampler::set(const RowPlane& plane, cv::Size size) {
  size_ = size;
  runs_.clear();
  row_runs_.assign(1, 0);
  col_base_.assign(size.height, 0);
  col_step_.assign(size.height, 0);
  const double cx = 0.5 * size.width, cy = 0.5 * size.height;
  for (int y = 0; y < size.height; ++y) {
    const double v = y - cy;
    for (int x = 0; x < size.width; ++x) {
      int row, step;
      split(y + plane.offset_px + plane.slope_x * (x - cx) + plane.slope_y * v, row, step);
      if (runs_.size() > static_cast<size_t>(row_runs_.back()) && runs_.back().row == row && runs_.back().step == step)
        runs_.back().x1 = x + 1;
      else
        runs_.push_back({x, x + 1, row, step});
    }
    row_runs_.push_back(static_cast<int>(runs_.size()));
    split(-plane.slope_x * v, col_base_[y], col_step_[y]);
  }
}

const cv::Mat& PlaneResampler::apply(const cv::Mat& in) {
  CV_Assert(in.type() == CV_8UC1 && in.size() == size_);
  const int w = size_.width, h = size_.height;
  rows_.create(size_, CV_8UC1);
  acc_.resize(w);
  // The column pass: each run of columns read at its row and step, eight rows of weights.
  for (int y = 0; y < h; ++y) {
    std::fill(acc_.begin(), acc_.end(), 0);
    int32_t* acc = acc_.data();
    for (int i = row_runs_[y]; i < row_runs_[y + 1]; ++i) {
      const Run& r = runs_[i];
      const int16_t* wt = weights(r.step);
      for (int k = 0; k < kTaps; ++k) {
        if (wt[k] == 0) continue;
        const int32_t wk = wt[k];
        const uint8_t* src = in.ptr<uint8_t>(std::clamp(r.row - 3 + k, 0, h - 1));
        for (int x = r.x0; x < r.x1; ++x) acc[x] += wk * src[x];
      }
    }
    uint8_t* dst = rows_.ptr<uint8_t>(y);
    for (int x = 0; x < w; ++x) dst[x] = saturate(acc[x]);
  }
  // The row pass: each row moved by its column shift (none for a plane without a turn).
  out_.create(size_, CV_8UC1);
  int reach = 0;
  for (int y = 0; y < h; ++y) reach = std::max(reach, std::abs(col_base_[y]));
  const int pad = kTaps + reach;
  padded_.resize(w + 2 * pad);
  for (int y = 0; y < h; ++y) {
    const uint8_t* src = rows_.ptr<uint8_t>(y);
    uint8_t* dst = out_.ptr<uint8_t>(y);
    if (col_base_[y] == 0 && col_step_[y] == 0) {
      std::memcpy(dst, src, w);
      continue;
    }
    std::memset(padded_.data(), src[0], pad);
    std::memcpy(padded_.data() + pad, src, w);
    std::memset(padded_.data() + pad + w, src[w - 1], pad);
    const int16_t* wt = weights(col_step_[y]);
    const uint8_t* first = padded_.data() + pad + col_base_[y] - 3;
    std::fill(acc_.begin(), acc_.end(), 0);
    int32_t* acc = acc_.data();
    for (int k = 0; k < kTaps; ++k) {
      if (wt[k] == 0) continue;
      const int32_t wk = wt[k];
      const uint8_t* s = first + k;
      for (int x = 0; x < w; ++x) acc[x] += wk * s[x];
    }
    for (int x = 0; x < w; ++x) dst[x] = saturate(acc[x]);
  }
  return out_;
}

}  // namespace nerv::stereo

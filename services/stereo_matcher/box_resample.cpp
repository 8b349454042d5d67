#include "box_resample.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

namespace nerv::stereo {

namespace {

// One output row: `sums` holds the column sums of `ny` source rows. The whole blocks
// divide by a constant when K is known at compile time (2 and 4, the factors the
// matcher uses) and ny == K; otherwise by n at run time.
template <int K>
void blockRow(const uint16_t* sums, int cols, int k, int ny, uint8_t* out) {
  const int kk = K > 0 ? K : k;
  const int whole = cols / kk;
  if (K > 0 && ny == K) {
    constexpr int n = K * K;
    for (int bx = 0; bx < whole; ++bx) {
      unsigned s = 0;
      for (int j = 0; j < K; ++j) s += sums[bx * K + j];
      out[bx] = static_cast<uint8_t>((s + n / 2) / n);
    }
  } else {
    const unsigned n = static_cast<unsigned>(ny * kk);
    for (int bx = 0; bx < whole; ++bx) {
      unsigned s = 0;
      for (int j = 0; j < kk; ++j) s += sums[bx * kk + j];
      out[bx] = static_cast<uint8_t>((s + n / 2) / n);
    }
  }
  const int rest = cols - whole * kk;
  if (rest > 0) {
    unsigned s = 0;
    for (int j = 0; j < rest; ++j) s += sums[whole * kk + j];
    const unsigned n = static_cast<unsigned>(ny * rest);
    out[whole] = static_cast<uint8_t>((s + n / 2) / n);
  }
}

template <int K>
void downscale(const cv::Mat& src, int k, cv::Mat& dst) {
  std::vector<uint16_t> sums(static_cast<size_t>(src.cols));
  for (int by = 0; by < dst.rows; ++by) {
    const int y0 = by * k;
    const int ny = std::min(k, src.rows - y0);
    const uint8_t* first = src.ptr<uint8_t>(y0);
    for (int x = 0; x < src.cols; ++x) sums[x] = first[x];
    for (int r = 1; r < ny; ++r) {
      const uint8_t* row = src.ptr<uint8_t>(y0 + r);
      for (int x = 0; x < src.cols; ++x) sums[x] = static_cast<uint16_t>(sums[x] + row[x]);
    }
    blockRow<K>(sums.data(), src.cols, k, ny, dst.ptr<uint8_t>(by));
  }
}

// out[x] = in[x / k] for elements of type T (by value, bit for bit).
template <typename T>
void spread(const uint8_t* in, uint8_t* out, int width, int k) {
  for (int x = 0; x < width; ++x) {
    T v;
    std::memcpy(&v, in + sizeof(T) * static_cast<size_t>(x / k), sizeof(T));
    std::memcpy(out + sizeof(T) * static_cast<size_t>(x), &v, sizeof(T));
  }
}

}  // namespace

void boxMeanDownscale(const cv::Mat& input, int k, cv::Mat& dst) {
  CV_Assert(input.type() == CV_8UC1 && k >= 1 && k <= 16);
  const cv::Mat src = input;  // a header of its own: dst may be the same Mat
  if (src.data == dst.data) dst = cv::Mat();  // never write what is being read
  dst.create((src.rows + k - 1) / k, (src.cols + k - 1) / k, CV_8UC1);
  if (src.empty()) return;
  switch (k) {
    case 1: src.copyTo(dst); break;
    case 2: downscale<2>(src, k, dst); break;
    case 4: downscale<4>(src, k, dst); break;
    default: downscale<0>(src, k, dst); break;
  }
}

void blockNearestUpscale(const cv::Mat& input, int k, cv::Size size, cv::Mat& dst) {
  CV_Assert(k >= 1 && input.rows == (size.height + k - 1) / k && input.cols == (size.width + k - 1) / k);
  const cv::Mat src = input;
  if (src.data == dst.data) dst = cv::Mat();
  dst.create(size, src.type());
  const size_t elem = src.elemSize();
  for (int y = 0; y < size.height; ++y) {
    const uint8_t* in = src.ptr<uint8_t>(y / k);
    uint8_t* out = dst.ptr<uint8_t>(y);
    if (y % k != 0) {  // the same source row as the row above
      std::memcpy(out, dst.ptr<uint8_t>(y - 1), elem * static_cast<size_t>(size.width));
      continue;
    }
    switch (elem) {
      case 4: spread<uint32_t>(in, out, size.width, k); break;
      case 2: spread<uint16_t>(in, out, size.width, k); break;
      case 1: spread<uint8_t>(in, out, size.width, k); break;
      default:
        for (int x = 0; x < size.width; ++x) std::memcpy(out + elem * x, in + elem * (x / k), elem);
    }
  }
}

}  // namespace nerv::stereo

#include "census_transform.hpp"

#include <vector>

namespace nerv::stereo {

void censusTransform(const cv::Mat& gray, int ww, int wh, cv::Mat& census, int row_begin,
                     int row_end) {
  CV_Assert(gray.type() == CV_8UC1 && census.type() == CV_32SC2 && census.size() == gray.size());
  const int rw = ww / 2, rh = wh / 2, cols = gray.cols;
  std::vector<uint8_t> planes;
  for (int y = row_begin; y < row_end; ++y) {
    uint64_t* out = census.ptr<uint64_t>(y);
    if (y < rh || y >= gray.rows - rh || cols <= 2 * rw) {
      std::fill(out, out + cols, uint64_t{0});
      continue;
    }
    const uint8_t* centre = gray.ptr<uint8_t>(y);
    // Comparisons are collected in byte planes (plane g holds bits 8g..8g+7),
    // so the inner loop compares 32 pixels per AVX2 instruction; the planes are
    // then interleaved into one uint64 per pixel.
    planes.assign(static_cast<size_t>(8) * cols, 0);
    int bit = ww * wh - 2;  // the first offset takes the highest used bit
    for (int dy = -rh; dy <= rh; ++dy) {
      const uint8_t* row = gray.ptr<uint8_t>(y + dy);
      for (int dx = -rw; dx <= rw; ++dx) {
        if (dx == 0 && dy == 0) continue;
        uint8_t* plane = planes.data() + static_cast<size_t>(bit >> 3) * cols;
        const int shift = bit & 7;
        for (int x = rw; x < cols - rw; ++x)
          plane[x] |= static_cast<uint8_t>((row[x + dx] < centre[x]) << shift);
        --bit;
      }
    }
    for (int x = 0; x < cols; ++x) {
      uint64_t v = 0;
      for (int g = 0; g < 8; ++g) v |= static_cast<uint64_t>(planes[static_cast<size_t>(g) * cols + x]) << (8 * g);
      out[x] = v;
    }
    for (int x = 0; x < rw; ++x) out[x] = out[cols - 1 - x] = 0;
  }
}

void censusTransform(const cv::Mat& gray, int ww, int wh, cv::Mat& census) {
  census.create(gray.size(), CV_32SC2);
  censusTransform(gray, ww, wh, census, 0, gray.rows);
}

}  // namespace nerv::stereo

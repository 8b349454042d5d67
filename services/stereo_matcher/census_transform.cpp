#include "census_transform.hpp"

#include <vector>

namespace nerv::stereo {

void censusTransform(const cv::Mat& gray, int ww, int wh, cv::Mat& census, int row_begin,
                     int row_end) {
  CV_Assert(gray.type() == CV_8UC1 && census.type() == CV_32SC1 && census.size() == gray.size());
  CV_Assert(censusBits(ww, wh) <= 32);
  const int rw = ww / 2, rh = wh / 2, cols = gray.cols;
  std::vector<uint8_t> planes;
  for (int y = row_begin; y < row_end; ++y) {
    uint32_t* out = census.ptr<uint32_t>(y);
    std::fill(out, out + cols, uint32_t{0});
    if (y < rh || y >= gray.rows - rh || cols <= 2 * rw) continue;
    // Comparisons are collected in byte planes (plane g holds bits 8g..8g+7),
    // so the inner loop compares 32 pixels per AVX2 instruction; the planes are
    // then interleaved into one uint32 per pixel.
    planes.assign(static_cast<size_t>(4) * cols, 0);
    int bit = censusBits(ww, wh) - 1;  // the first pair takes the highest used bit
    for (int dy = -rh; dy <= 0; ++dy) {
      const uint8_t* row = gray.ptr<uint8_t>(y + dy);
      const uint8_t* mirror = gray.ptr<uint8_t>(y - dy);
      for (int dx = -rw; dx <= rw; ++dx) {
        if (dy == 0 && dx >= 0) break;  // the centre and the mirrored half
        uint8_t* plane = planes.data() + static_cast<size_t>(bit >> 3) * cols;
        const int shift = bit & 7;
        for (int x = rw; x < cols - rw; ++x)
          plane[x] |= static_cast<uint8_t>((row[x + dx] < mirror[x - dx]) << shift);
        --bit;
      }
    }
    for (int x = rw; x < cols - rw; ++x) {
      uint32_t v = 0;
      for (int g = 0; g < 4; ++g) v |= static_cast<uint32_t>(planes[static_cast<size_t>(g) * cols + x]) << (8 * g);
      out[x] = v;
    }
  }
}

void censusTransform(const cv::Mat& gray, int ww, int wh, cv::Mat& census) {
  census.create(gray.size(), CV_32SC1);
  censusTransform(gray, ww, wh, census, 0, gray.rows);
}

}  // namespace nerv::stereo

#include "delta16_codec.hpp"

namespace nerv {

void encodeDelta16(const cv::Mat& fixed, std::vector<uint8_t>& out) {
  CV_Assert(fixed.type() == CV_16U);
  out.resize(delta16MaxBytes(fixed.cols, fixed.rows));
  uint8_t* o = out.data();
  int prev_row_first = 0;
  for (int v = 0; v < fixed.rows; ++v) {
    const uint16_t* row = fixed.ptr<uint16_t>(v);
    int prev = prev_row_first;
    for (int u = 0; u < fixed.cols; ++u) {
      const int diff = static_cast<int>(row[u]) - prev;
      prev = row[u];
      // zigzag: 0, -1, 1, -2, ... -> 0, 1, 2, 3, ... (shifted as unsigned: a negative left shift is UB in C++17)
      uint32_t z = (static_cast<uint32_t>(diff) << 1) ^ static_cast<uint32_t>(diff >> 31);
      while (z >= 0x80) {
        *o++ = static_cast<uint8_t>(z | 0x80);
        z >>= 7;
      }
      *o++ = static_cast<uint8_t>(z);
    }
    if (fixed.cols > 0) prev_row_first = row[0];
  }
  out.resize(static_cast<size_t>(o - out.data()));
}

std::string decodeDelta16(const uint8_t* data, size_t size, int width, int height, cv::Mat& fixed) {
  if (width <= 0 || height <= 0) return "delta16 disparity has no pixels";
  fixed.create(height, width, CV_16U);
  const uint8_t* p = data;
  const uint8_t* const end = data + size;
  int prev_row_first = 0;
  for (int v = 0; v < height; ++v) {
    uint16_t* row = fixed.ptr<uint16_t>(v);
    int prev = prev_row_first;
    for (int u = 0; u < width; ++u) {
      uint32_t z = 0;
      for (int shift = 0;; shift += 7) {
        if (p == end) return "delta16 stream ends at row " + std::to_string(v) + ", column " + std::to_string(u);
        if (shift > 14) return "delta16 value at row " + std::to_string(v) + " runs over 3 bytes";
        const uint8_t b = *p++;
        z |= static_cast<uint32_t>(b & 0x7f) << shift;
        if (!(b & 0x80)) break;
      }
      const int diff = static_cast<int>(z >> 1) ^ -static_cast<int>(z & 1);
      const int value = prev + diff;
      if (value < 0 || value > 65535)
        return "delta16 value " + std::to_string(value) + " at row " + std::to_string(v) + " is not a uint16";
      row[u] = static_cast<uint16_t>(value);
      prev = value;
    }
    prev_row_first = row[0];
  }
  if (p != end) return "delta16 stream has " + std::to_string(end - p) + " bytes after the last pixel";
  return "";
}

}  // namespace nerv

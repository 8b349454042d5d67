#include "census_transform.hpp"

namespace nerv::stereo {

void censusTransform(const cv::Mat& gray, int ww, int wh, cv::Mat& census, int row_begin,
                     int row_end) {
  CV_Assert(gray.type() == CV_8UC1 && census.type() == CV_32SC2 && census.size() == gray.size());
  const int rw = ww / 2, rh = wh / 2, cols = gray.cols;
  for (int y = row_begin; y < row_end; ++y) {
    uint64_t* out = census.ptr<uint64_t>(y);
    if (y < rh || y >= gray.rows - rh || cols <= 2 * rw) {
      std::fill(out, out + cols, uint64_t{0});
      continue;
    }
    const uint8_t* centre = gray.ptr<uint8_t>(y);
    std::fill(out, out + cols, uint64_t{0});
    // Offset-major: the inner loop over x is a plain compare-shift-or that the
    // compiler vectorises.
    for (int dy = -rh; dy <= rh; ++dy) {
      const uint8_t* row = gray.ptr<uint8_t>(y + dy);
      for (int dx = -rw; dx <= rw; ++dx) {
        if (dx == 0 && dy == 0) continue;
        for (int x = rw; x < cols - rw; ++x)
          out[x] = (out[x] << 1) | static_cast<uint64_t>(row[x + dx] < centre[x]);
      }
    }
    for (int x = 0; x < rw; ++x) out[x] = out[cols - 1 - x] = 0;
  }
}

void censusTransform(const cv::Mat& gray, int ww, int wh, cv::Mat& census) {
  census.create(gray.size(), CV_32SC2);
  censusTransform(gray, ww, wh, census, 0, gray.rows);
}

}  // namespace nerv::stereo

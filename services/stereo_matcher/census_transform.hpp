// Center-symmetric census transform: each pixel becomes a bit string saying,
// for every pair of pixels placed symmetrically about it in a window, whether
// the first is darker than its mirror (Spangenberg et al. 2013, "Weighted
// semi-global matching and center-symmetric census transform for robust
// driver assistance"). Robust to gain and offset differences between the
// cameras like the plain census, with half the bits: a 9x7 window gives 31
// bits, one uint32 per pixel. On KITTI 2015 000005, the synthetic urban set
// and Middlebury Aloe it matched as well as or better than the 62-bit plain
// census (docs/stereo.md).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

namespace nerv::stereo {

// Bits of a window: (width * height - 1) / 2 (at most 32).
inline int censusBits(int window_width, int window_height) {
  return (window_width * window_height - 1) / 2;
}

// gray: CV_8UC1. census: CV_32SC1 of the same size holding one uint32 per
// pixel; read it with census.ptr<uint32_t>(y). Pairs: the offsets (dy, dx)
// before the centre in row-major order (dy < 0, or dy == 0 and dx < 0), each
// with its mirror (-dy, -dx); the first pair takes the highest used bit; bit =
// 1 when I(y + dy, x + dx) < I(y - dy, x - dx). Pixels closer than the half
// window to the border get census 0. Rows [row_begin, row_end) only (for
// stripes); `census` must be allocated.
void censusTransform(const cv::Mat& gray, int window_width, int window_height, cv::Mat& census,
                     int row_begin, int row_end);

// Allocates `census` and transforms every row.
void censusTransform(const cv::Mat& gray, int window_width, int window_height, cv::Mat& census);

}  // namespace nerv::stereo

// Census transform (Zabih & Woodfill 1994): each pixel becomes a bit string
// saying which neighbours in a window are darker than it. Robust to gain and
// offset differences between the cameras, which is what makes it the usual SGM
// matching cost on real roads.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

namespace nerv::stereo {

// gray: CV_8UC1. census: CV_32SC2 (8 bytes per pixel) holding one uint64 per
// pixel; read it with census.ptr<uint64_t>(y).
// Bit order: window offsets row-major (dy from -h/2, dx from -w/2), centre
// skipped, first offset in the highest used bit; bit = 1 when neighbour < centre.
// Pixels closer than the half window to the border get census 0. Rows
// [row_begin, row_end) only (for stripes); `census` must be allocated.
void censusTransform(const cv::Mat& gray, int window_width, int window_height, cv::Mat& census,
                     int row_begin, int row_end);

// Allocates `census` and transforms every row.
void censusTransform(const cv::Mat& gray, int window_width, int window_height, cv::Mat& census);

}  // namespace nerv::stereo

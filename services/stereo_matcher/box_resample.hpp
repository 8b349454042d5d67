// Images made smaller by a whole factor for a coarser match, and its disparity made
// full size again, in integer arithmetic of our own so that every build gives the same
// bytes. OpenCV's INTER_AREA resize, used here before, takes a fractional scale when a
// side is not a multiple of the factor (375 rows / 188 = 1.995) and ran a different
// code path on aarch64: `nerv_sgm downscale 2` read D1 12.67 % there against 13.05 %
// on x86 for the same pair (docs/stereo.md "Halving the views").
//
// boxMeanDownscale: block (by, bx) of the output is the rounded mean of source rows
// [k by, k by + k) and columns [k bx, k bx + k), cut at the image's edge (a last
// block of fewer pixels is the mean of those it has); output size ceil(rows / k) x
// ceil(cols / k). Rounding: (sum + n / 2) / n, the same as INTER_AREA gives for an
// exact factor.
//
// blockNearestUpscale: output pixel (y, x) = source pixel (y / k, x / k), any
// element type: the inverse of the block layout above, so a disparity value stays on
// the pixels it was measured for and an invalid one stays invalid.
#pragma once

#include <opencv2/core.hpp>

namespace nerv::stereo {

// src: CV_8UC1, k in [1, 16]. dst is (re)allocated.
void boxMeanDownscale(const cv::Mat& src, int k, cv::Mat& dst);

// src: any single- or multi-channel type; size must be ceil(size / k) per side.
void blockNearestUpscale(const cv::Mat& src, int k, cv::Size size, cv::Mat& dst);

}  // namespace nerv::stereo

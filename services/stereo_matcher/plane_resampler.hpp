// An 8-bit view resampled by a row plane with a Lanczos kernel (a = 4, 8 taps), separably and
// fast. The right view's row correction (view_correction.hpp) reads each pixel at
//
//   out(x, y) = in(x - b v, y + a + b u + c v),   u = x - W/2, v = y - H/2.
//
// Bilinear resampling at a fractional row averages two rows: it blurs the view by up to a
// [1/2 1/2] filter, and the census matcher loses fine texture with it (KITTI 0926 with the right
// view resampled half a row forth and back, nothing else changed: F1 0.919 -> 0.800). A Lanczos
// kernel keeps the texture up to near the Nyquist frequency; OpenCV's remap has one, but in two
// dimensions (64 taps a pixel, 8-14 ms a KITTI frame). Here the same kernel is applied as two
// passes of 8 taps: first each column is read at its own fractional row, in runs of columns that
// share the row and the step (the plane's column slope is a few thousandths, so the runs are
// tens of columns long and each is eight row-vector multiply-adds); then each row is moved by its
// own fractional column (b v is constant along a row). Rows and columns in steps of 1/32 px, as
// OpenCV's fixed-point maps; weights in 1/16384; the border repeated. Reading the column pass at
// x - b v instead of x changes the row read there by b^2 v, below 1e-5 px.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "row_plane.hpp"

namespace nerv::stereo {

class PlaneResampler {
 public:
  // The plane and the view size the next apply() calls resample by (the runs built once here).
  void set(const RowPlane& plane, cv::Size size);
  // in: 8-bit gray of the size given to set(). out: in resampled (a buffer of this object,
  // valid until the next call).
  const cv::Mat& apply(const cv::Mat& in);

  static constexpr int kTaps = 8;     // Lanczos a = 4
  static constexpr int kSteps = 32;   // fractional positions per pixel
  static constexpr int kShift = 14;   // weights in 1 / 2^kShift
  // The weights of the taps at floor(p) - 3 .. floor(p) + 4 for p's fraction q / kSteps; they sum
  // to 2^kShift.
  static const int16_t* weights(int q);

 private:
  struct Run {
    int x0, x1;  // columns [x0, x1)
    int row;     // floor of the row read
    int step;    // its fraction, in 1 / kSteps
  };
  cv::Size size_;
  std::vector<Run> runs_;          // every output row's runs, row after row
  std::vector<int> row_runs_;      // index of each row's first run; size rows + 1
  std::vector<int> col_base_;      // per row: floor of the column shift - b v
  std::vector<int> col_step_;      // its fraction, in 1 / kSteps
  cv::Mat rows_, out_;             // after the column pass; after both
  std::vector<int32_t> acc_;       // one row of sums
  std::vector<uint8_t> padded_;    // one row with its border repeated, for the row pass
};

}  // namespace nerv::stereo

// v-disparity: one disparity histogram per image row (Labayrade et al. 2002).
// A plane road becomes a straight line d = a*v + b in it, upright obstacles become
// vertical segments; the ground fit works on this small image, not on pixels.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace nerv::stixel {

struct VDisparity {
  int rows = 0;                 // image rows
  int bins = 0;                 // disparity bins of 1 px: bin k holds [k, k+1)
  std::vector<int> count;       // rows x bins, pixels per cell
  std::vector<float> sum_d;     // rows x bins, sum of the cell's disparities
  int valid_pixels = 0;          // of the sampled columns
  int sampled_columns = 0;       // columns that voted (every column_step-th)

  int cellCount(int v, int k) const { return count[static_cast<size_t>(v) * bins + k]; }
  // Mean disparity of a cell: keeps the fit sub-pixel although the bins are 1 px.
  float cellMean(int v, int k) const {
    const size_t i = static_cast<size_t>(v) * bins + k;
    return count[i] > 0 ? sum_d[i] / static_cast<float>(count[i]) : k + 0.5f;
  }
};

// disparity: CV_32F; values <= 0, non-finite or >= max_disparity_px are skipped.
// column_step > 1 samples every column_step-th column: the road covers hundreds of
// pixels per row, so half of them fix its histogram mode as well (and twice as fast).
VDisparity computeVDisparity(const cv::Mat& disparity, float max_disparity_px,
                             int column_step = 1);

// True for a usable disparity value (positive, finite, below the histogram range).
inline bool validDisparity(float d, float max_disparity_px) {
  // Written so that NaN fails both comparisons and +inf fails the second.
  return d > 0.0f && d < max_disparity_px;
}

}  // namespace nerv::stixel

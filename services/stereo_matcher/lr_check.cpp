#include "lr_check.hpp"

#include <cstdlib>

namespace nerv::stereo {

void leftRightCheckRow(const int16_t* best_left, const int16_t* best_right, int cols,
                       int min_disparity, int max_diff, float* disparity, float* confidence) {
  for (int x = 0; x < cols; ++x) {
    const int d = best_left[x];
    if (d < 0) continue;
    const int xr = x - min_disparity - d;
    const bool ok = xr >= 0 && best_right[xr] >= 0 && std::abs(best_right[xr] - d) <= max_diff;
    if (!ok) {
      disparity[x] = -1.0f;
      confidence[x] = 0.0f;
    }
  }
}

}  // namespace nerv::stereo

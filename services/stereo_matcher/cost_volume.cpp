#include "cost_volume.hpp"

#include <algorithm>

namespace nerv::stereo {

void reverseCensusRow(const uint32_t* right, int cols, int min_disparity, int num_disparities,
                      uint32_t* reversed) {
  std::reverse_copy(right, right + cols, reversed);
  std::fill(reversed + cols, reversed + cols + min_disparity + num_disparities, right[0]);
}

void censusCostRange(const uint32_t* left, const uint32_t* right_reversed, int cols, int x0, int x1,
                     int min_disparity, int num_disparities, uint8_t* out) {
  for (int x = x0; x < x1; ++x) {
    const uint32_t l = left[x];
    const uint32_t* r = right_reversed + (cols - 1 - x) + min_disparity;
    uint8_t* c = out + static_cast<size_t>(x - x0) * num_disparities;
    for (int d = 0; d < num_disparities; ++d)
      c[d] = static_cast<uint8_t>(__builtin_popcount(l ^ r[d]));
  }
}

}  // namespace nerv::stereo

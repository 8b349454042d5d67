#include "cost_volume.hpp"

#include <algorithm>

namespace nerv::stereo {

void censusCostRow(const uint64_t* left, const uint64_t* right, int cols, int min_disparity,
                   int num_disparities, uint8_t* out, std::vector<uint64_t>& reversed) {
  // Reversed right row: reversed[j] = right[cols - 1 - j] (column 0 beyond the
  // edge), so the D right codes a left pixel is compared with are contiguous and
  // in disparity order, and the inner loop vectorises (XOR + popcount + narrow).
  const int n = cols + min_disparity + num_disparities;
  reversed.resize(n);
  for (int j = 0; j < n; ++j) reversed[j] = right[std::max(0, cols - 1 - j)];
  for (int x = 0; x < cols; ++x) {
    const uint64_t l = left[x];
    const uint64_t* r = reversed.data() + (cols - 1 - x) + min_disparity;
    uint8_t* c = out + static_cast<size_t>(x) * num_disparities;
    for (int d = 0; d < num_disparities; ++d)
      c[d] = static_cast<uint8_t>(__builtin_popcountll(l ^ r[d]));
  }
}

}  // namespace nerv::stereo

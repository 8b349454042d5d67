// The k-th smallest of a set of floats, exactly: the value std::nth_element
// leaves at position k, found by a radix select on the floats' bit patterns
// (ordered like the values once the sign is folded) instead of a partition
// whose every comparison is a branch the processor mispredicts half the time.
// Three passes of 11, 11 and 10 bits; each after the first only over the
// values whose higher bits matched. The IRLS plane fit takes a median of
// ~5000 residuals per iteration (docs/snv.md "Speed").
//
// Zeros: -0 sorts before +0 here (std::nth_element holds them equal and may
// return either). NaNs sort above +inf (a NaN would leave std::nth_element's
// result unspecified).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nerv::snv {

// k < n. scratch: reused between calls (no allocation once it has grown).
float kthSmallest(const float* values, size_t n, size_t k, std::vector<uint32_t>& scratch);

}  // namespace nerv::snv

#include "order_statistic.hpp"

#include <cstring>

namespace nerv::snv {

namespace {

// Unsigned key in the order of the values: negative floats have every bit
// flipped (larger magnitude = smaller), positive ones only the sign bit.
inline uint32_t orderKey(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b ^ (static_cast<uint32_t>(static_cast<int32_t>(b) >> 31) | 0x80000000u);
}

inline float fromKey(uint32_t k) {
  const uint32_t b = k ^ ((k & 0x80000000u) ? 0x80000000u : 0xffffffffu);
  float x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// The digit (shift, bits) whose cumulative count passes k; k becomes the rank
// inside that digit's bucket.
template <class Keys>
uint32_t selectDigit(const Keys& keys, size_t n, int shift, uint32_t mask, size_t& k) {
  uint32_t count[2048] = {};
  for (size_t i = 0; i < n; ++i) ++count[(keys(i) >> shift) & mask];
  uint32_t digit = 0;
  while (k >= count[digit]) k -= count[digit++];
  return digit;
}

}  // namespace

float kthSmallest(const float* values, size_t n, size_t k, std::vector<uint32_t>& scratch) {
  // Top 11 bits over all values.
  const uint32_t d1 = selectDigit([&](size_t i) { return orderKey(values[i]); }, n, 21, 0x7ffu, k);
  scratch.clear();
  for (size_t i = 0; i < n; ++i) {
    const uint32_t key = orderKey(values[i]);
    if ((key >> 21) == d1) scratch.push_back(key);
  }
  // The next 11 bits, then the last 10, over the bucket's keys only.
  const size_t m = scratch.size();
  const uint32_t d2 = selectDigit([&](size_t i) { return scratch[i]; }, m, 10, 0x7ffu, k);
  size_t kept = 0;
  for (size_t i = 0; i < m; ++i)
    if (((scratch[i] >> 10) & 0x7ffu) == d2) scratch[kept++] = scratch[i];
  const uint32_t d3 = selectDigit([&](size_t i) { return scratch[i]; }, kept, 0, 0x3ffu, k);
  return fromKey((d1 << 21) | (d2 << 10) | d3);
}

}  // namespace nerv::snv

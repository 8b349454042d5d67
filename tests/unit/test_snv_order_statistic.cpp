// kthSmallest against std::nth_element (the value it leaves at k) on the
// inputs the plane fit and other callers give it, and on adversarial ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "order_statistic.hpp"

namespace nerv::snv {
namespace {

float byNthElement(std::vector<float> v, size_t k) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectAllRanks(const std::vector<float>& v, const char* what) {
  std::vector<uint32_t> scratch;
  std::vector<float> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  for (size_t k = 0; k < v.size(); ++k) {
    const float got = kthSmallest(v.data(), v.size(), k, scratch);
    ASSERT_TRUE(sameBits(got, sorted[k])) << what << ": rank " << k << " of " << v.size() << ": " << got
                                          << " instead of " << sorted[k];
  }
}

TEST(snvOrderStatistic, EqualsNthElementOnResidualLikeData) {
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::uniform_real_distribution<float> outlier(-0.3f, 0.3f);
  std::vector<uint32_t> scratch;
  for (int trial = 0; trial < 200; ++trial) {
    const size_t n = 1 + rng() % 6000;
    std::vector<float> v(n);
    for (auto& x : v) x = std::abs(rng() % 5 == 0 ? outlier(rng) : noise(rng));  // |relative residual|
    const size_t k = n / 2;
    const float want = byNthElement(v, k);
    const float got = kthSmallest(v.data(), n, k, scratch);
    ASSERT_TRUE(sameBits(got, want)) << "trial " << trial << ", n " << n;
  }
}

TEST(snvOrderStatistic, EveryRankOfSignedTiedAndExtremeValues) {
  expectAllRanks({5.0f}, "one value");
  expectAllRanks({2.0f, 2.0f, 2.0f, 2.0f}, "all equal");
  expectAllRanks({-1.5f, 3.0f, -1e-30f, 1e-30f, 0.0f, -7.25f, 3.0f, -1.5f,
                  std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::max(),
                  std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity(),
                  -std::numeric_limits<float>::infinity()},
                 "signed, tied, denormal and infinite");
  // Values that share their first 21 bits and differ only in the last ones.
  std::vector<float> close;
  for (int i = 0; i < 300; ++i) close.push_back(std::nextafter(1.0f, 2.0f) + static_cast<float>((i * 37) % 300) * 1e-7f);
  expectAllRanks(close, "one high bucket");
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> any(-100.0f, 100.0f);
  std::vector<float> random(997);
  for (auto& x : random) x = any(rng);
  expectAllRanks(random, "uniform");
}

TEST(snvOrderStatistic, ZerosSortNegativeFirstAndNanLast) {
  std::vector<uint32_t> scratch;
  const std::vector<float> v = {0.0f, -0.0f, 1.0f, std::numeric_limits<float>::quiet_NaN()};
  EXPECT_TRUE(std::signbit(kthSmallest(v.data(), v.size(), 0, scratch)));
  EXPECT_FALSE(std::signbit(kthSmallest(v.data(), v.size(), 1, scratch)));
  EXPECT_EQ(kthSmallest(v.data(), v.size(), 2, scratch), 1.0f);
  EXPECT_TRUE(std::isnan(kthSmallest(v.data(), v.size(), 3, scratch)));
}

}  // namespace
}  // namespace nerv::snv

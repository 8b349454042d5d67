// Super-SNV statistics: histogram mode, adaptive mean shift against a brute
// force search, entropy definition and ordering, angle conventions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "adaptive_mean_shift.hpp"
#include "camera_height.hpp"
#include "entropy.hpp"
#include "super_snv.hpp"

namespace nerv::snv {
namespace {

// A skewed pitch sample like real ground normals: a tight core at `core` and
// a long one-sided tail (SGBM's fronto-parallel bias tips far road normals).
std::vector<float> skewedSample(int n, float core, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> body(core, 0.25f);
  std::exponential_distribution<float> tail(1.0f / 1.5f);
  std::vector<float> v;
  for (int i = 0; i < n; ++i) v.push_back(i % 10 < 6 ? body(rng) : core + 0.2f + tail(rng));
  return v;
}

// Brute force: every iteration sorts all distances to the centre.
float bruteForceMeanShift(const std::vector<float>& values, float start, float fraction, float stop) {
  const int n = static_cast<int>(values.size());
  const int k = std::clamp(static_cast<int>(std::ceil(fraction * n)), 1, n);
  double c = start;
  for (int it = 0; it < 100; ++it) {
    std::vector<std::pair<double, float>> by_distance;
    for (float x : values) by_distance.push_back({std::abs(x - c), x});
    std::sort(by_distance.begin(), by_distance.end());
    double sum = 0;
    for (int i = 0; i < k; ++i) sum += by_distance[i].second;
    const double next = sum / k;
    const double moved = std::abs(next - c);
    c = next;
    if (moved < stop) break;
  }
  return static_cast<float>(c);
}

TEST(snvSuperSnv, HistogramModeAndBins) {
  const std::vector<float> v = {0.01f, 0.02f, 0.13f, 0.14f, 0.15f, -0.33f, 0.19f};
  const AngleHistogram h = buildAngleHistogram(v, 0.1f);
  EXPECT_NEAR(h.origin_deg, -0.4f, 1e-6);
  ASSERT_EQ(h.counts.size(), 6u);  // [-0.4, 0.2)
  EXPECT_EQ(std::accumulate(h.counts.begin(), h.counts.end(), 0), 7);
  EXPECT_NEAR(h.modeDeg(), 0.15f, 1e-5);  // 0.13, 0.14, 0.15, 0.19 in [0.1, 0.2)
  EXPECT_TRUE(std::isnan(buildAngleHistogram({}, 0.1f).modeDeg()));
}

TEST(snvSuperSnv, AngleConventions) {
  // Camera looking down by 2 deg: the road normal tips towards -z.
  const cv::Vec3f n = normalFromPitchRoll(2.0f, -1.0f);
  EXPECT_LT(n[2], 0.0f);
  EXPECT_GT(n[0], 0.0f);  // rolled anticlockwise: normal leans to +x
  EXPECT_NEAR(normalPitchDeg(n), 2.0f, 1e-4);
  EXPECT_NEAR(normalRollDeg(n), -1.0f, 1e-4);
  // The reference's formula, with the sign adapted: acos(z / |(y,z)|) - 90 deg.
  const double ref = std::acos(n[2] / std::hypot(n[1], n[2])) * 180 / CV_PI - 90.0;
  EXPECT_NEAR(normalPitchDeg(n), ref, 1e-4);
}

TEST(snvMeanShift, MatchesBruteForceOnSkewedSample) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<float> v = skewedSample(4000, 0.4f, seed);
    const float mode = buildAngleHistogram(v, 0.1f).modeDeg();
    const float brute = bruteForceMeanShift(v, mode, 0.5f, 0.01f);
    std::sort(v.begin(), v.end());
    const MeanShiftResult ms = adaptiveMeanShift(v, mode, 0.5f, 0.01f);
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
    EXPECT_TRUE(ms.converged);
    EXPECT_EQ(ms.inliers, 2000);
    EXPECT_NEAR(ms.estimate, brute, 1e-4) << "seed " << seed;
    // The mean shift lands in the core; the mean is dragged into the tail.
    EXPECT_NEAR(ms.estimate, 0.4f, 0.15f);
    EXPECT_GT(mean, 0.4 + 0.4);
    // Its window really holds half of the sample.
    const auto inside = std::count_if(v.begin(), v.end(), [&](float x) {
      return std::abs(x - ms.estimate) <= ms.radius + 0.02f;
    });
    EXPECT_GE(inside, 2000);
  }
}

TEST(snvMeanShift, NearestRunIsTheKNearest) {
  std::vector<float> v = skewedSample(500, 0.0f, 9);
  std::sort(v.begin(), v.end());
  for (float c : {-1.0f, 0.0f, 0.3f, 2.5f, 9.0f}) {
    for (int k : {1, 50, 250, 500}) {
      const int b = nearestRunBegin(v, c, k);
      std::vector<float> d;
      for (float x : v) d.push_back(std::abs(x - c));
      std::sort(d.begin(), d.end());
      const float worst_in_run = std::max(std::abs(v[b] - c), std::abs(v[b + k - 1] - c));
      EXPECT_FLOAT_EQ(worst_in_run, d[k - 1]) << "c " << c << " k " << k;
    }
  }
}

TEST(snvMeanShift, SingleValueAndEmpty) {
  const MeanShiftResult ms = adaptiveMeanShift({1.25f}, 1.2f, 0.5f, 0.01f);
  EXPECT_FLOAT_EQ(ms.estimate, 1.25f);
  EXPECT_EQ(ms.inliers, 1);
  EXPECT_THROW(adaptiveMeanShift({}, 0.0f, 0.5f, 0.01f), std::invalid_argument);
}

TEST(snvEntropy, DefinitionOnExactHistograms) {
  // 8 values in 8 different 0.1 deg bins around 0: window of all = 3 bits.
  std::vector<float> v;
  for (int i = -4; i < 4; ++i) v.push_back(0.1f * i);
  EXPECT_NEAR(windowEntropyBits(v, -0.05f, 1.0f, 0.1f), 3.0, 1e-6);
  // A single bin: 0 bits, confidence 1.
  const std::vector<float> same(100, 0.7f);
  EXPECT_NEAR(windowEntropyBits(same, 0.7f, 0.5f, 0.1f), 0.0, 1e-9);
  EXPECT_FLOAT_EQ(entropyConfidence(0.0f, 6.0f), 1.0f);
  EXPECT_FLOAT_EQ(entropyConfidence(3.0f, 6.0f), 0.5f);
  EXPECT_FLOAT_EQ(entropyConfidence(9.0f, 6.0f), 0.0f);
}

TEST(snvEntropy, MeanAtLeastModeAboveMeanShift) {
  for (unsigned seed : {4u, 5u, 6u}) {
    // The skewed sample plus a spike of 13 % off the core, as SGBM's sub-pixel
    // locking produces: the histogram mode sits on the spike, not the core.
    std::vector<float> v = skewedSample(20000, -0.3f, seed);
    v.insert(v.end(), 3000, -0.85f);
    const float mode = buildAngleHistogram(v, 0.1f).modeDeg();
    const float mean = static_cast<float>(std::accumulate(v.begin(), v.end(), 0.0) / v.size());
    std::sort(v.begin(), v.end());
    const float shift = adaptiveMeanShift(v, mode, 0.5f, 0.01f).estimate;
    const float h_mean = windowEntropyBits(v, mean, 0.5f, 0.1f);
    const float h_mode = windowEntropyBits(v, mode, 0.5f, 0.1f);
    const float h_shift = windowEntropyBits(v, shift, 0.5f, 0.1f);
    std::printf("seed %u: mode %.3f mean %.3f shift %.3f | H mean %.3f >= H mode %.3f > H shift %.3f bits\n",
                seed, mode, mean, shift, h_mean, h_mode, h_shift);
    EXPECT_GE(h_mean, h_mode);
    EXPECT_GT(h_mode, h_shift);
  }
}

}  // namespace
}  // namespace nerv::snv

namespace nerv::snv {
namespace {

// Fast super-SNV paths against their references (STYLE.md: fast vs slow).
TEST(snvSuperSnvFast, SortAnglesEqualsStdSort) {
  auto expectSorted = [](std::vector<float> v, const char* what) {
    std::vector<float> ref = v;
    std::sort(ref.begin(), ref.end());
    sortAngles(v);
    ASSERT_EQ(v.size(), ref.size()) << what;
    for (size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i], ref[i]) << what << " " << i;
  };
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<float> v = skewedSample(20000 + 7 * seed, -0.3f * seed, seed);
    v.push_back(0.0f);
    v.push_back(-0.0f);
    v.push_back(-45.0f);
    v.push_back(1e-30f);
    expectSorted(v, "skewed");
  }
  // Adversarial for a bucket sort: duplicates, a far outlier, geometric spacing
  // (every level splits off only the largest value), tiny ranges, small sizes.
  std::mt19937 rng(7);
  std::vector<float> dup, outlier = skewedSample(5000, 0.5f, 9), geometric, tiny;
  for (int i = 0; i < 5000; ++i) dup.push_back(static_cast<float>(rng() % 7) / 16.0f);
  outlier.push_back(1e30f);
  outlier.push_back(-1e30f);
  std::vector<float> huge = skewedSample(5000, 0.5f, 10);  // a range that overflows float
  huge.push_back(3e38f);
  huge.push_back(-3e38f);
  expectSorted(huge, "huge range");
  for (int i = 0; i < 3000; ++i) geometric.push_back(std::ldexp(1.0f, -(i % 120)) * (i % 3 ? 1.0f : -1.0f));
  for (int i = 0; i < 3000; ++i) tiny.push_back(std::nextafter(1.0f, 2.0f + static_cast<float>(rng() % 3)));
  expectSorted(dup, "duplicates");
  expectSorted(outlier, "outlier");
  expectSorted(geometric, "geometric");
  expectSorted(tiny, "tiny range");
  expectSorted(std::vector<float>(1000, 2.5f), "all equal");
  for (int n = 0; n < 80; ++n) {
    std::vector<float> v = skewedSample(n, 0.0f, 100 + n);
    expectSorted(v, "small");
  }
}

TEST(snvSuperSnvFast, SortedModeEqualsHistogramMode) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::vector<float> v = skewedSample(500 + 50 * seed, 0.37f * seed - 3.0f, seed);
    // Exact ties between bins: the first one wins in both.
    if (seed % 5 == 0) v = {0.05f, 0.05f, 0.25f, 0.25f, -1.0f};
    for (float bin : {0.1f, 0.05f, 0.5f}) {
      const float ref = buildAngleHistogram(v, bin).modeDeg();
      std::vector<float> s = v;
      sortAngles(s);
      EXPECT_EQ(sortedModeDeg(s, bin), ref) << "seed " << seed << " bin " << bin;
    }
  }
  EXPECT_TRUE(std::isnan(sortedModeDeg({}, 0.1f)));
}

// Reference: the median by std::nth_element (mean of the middle two when even).
float nthElementMedian(std::vector<float> v) {
  if (v.empty()) return std::numeric_limits<float>::quiet_NaN();
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5f * (*std::max_element(v.begin(), mid) + *mid);
}

TEST(snvSuperSnvFast, SampleMedianEqualsNthElement) {
  std::mt19937 rng(11);
  std::vector<std::vector<float>> cases;
  for (int n : {1, 2, 3, 255, 256, 257, 1000, 6547, 20000}) cases.push_back(skewedSample(n, 1.6f, n));
  std::vector<float> dup, spike = skewedSample(4000, 1.65f, 3);
  for (int i = 0; i < 4000; ++i) dup.push_back(static_cast<float>(rng() % 5) * 0.25f);
  spike.push_back(1e20f);  // one far outlier squeezes the rest into one bucket
  cases.push_back(dup);
  cases.push_back(spike);
  cases.push_back(std::vector<float>(600, 1.65f));
  for (const auto& v : cases) {
    const std::vector<float> before = v;
    EXPECT_EQ(sampleMedian(v), nthElementMedian(v)) << "n " << v.size();
    EXPECT_EQ(v, before);
  }
  EXPECT_TRUE(std::isnan(sampleMedian({})));
}

TEST(snvSuperSnvFast, PolynomialAnglesEqualAtan2) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> a(-70.0f, 70.0f);
  std::vector<cv::Vec3f> normals;
  for (int i = 0; i < 20000; ++i) normals.push_back(normalFromPitchRoll(a(rng), a(rng)));
  // Normals that do not point up take the std::atan2 path.
  normals.push_back(cv::Vec3f(0.3f, 0.2f, -0.93f));
  normals.push_back(cv::Vec3f(0.0f, 0.0f, -1.0f));
  normals.push_back(cv::Vec3f(-0.5f, -1e-8f, 0.5f));
  std::vector<float> pitch(normals.size()), roll(normals.size());
  normalAnglesDeg(normals.data(), static_cast<int>(normals.size()), pitch.data(), roll.data());
  double worst = 0;
  for (size_t i = 0; i < normals.size(); ++i) {
    worst = std::max(worst, std::abs(double(pitch[i]) - normalPitchDeg(normals[i])));
    worst = std::max(worst, std::abs(double(roll[i]) - normalRollDeg(normals[i])));
  }
  EXPECT_LT(worst * CV_PI / 180.0, 1e-6);  // rad
}

}  // namespace
}  // namespace nerv::snv

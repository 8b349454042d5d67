// nerv_sgm against a slow, obviously correct reference of the same census cost
// and 4-path aggregation; SIMD against scalar; known-disparity and occlusion scenes.
#include <gtest/gtest.h>

#include <tuple>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "census_transform.hpp"
#include "cost_volume.hpp"
#include "own_sgm.hpp"
#include "path_aggregation.hpp"
#include "winner_subpixel.hpp"
#include "stereo_matcher.hpp"
#include "stereo_reference_median_fill.hpp"

using namespace nerv::stereo;

namespace {

cv::Mat texture(int rows, int cols, unsigned seed, double blur_sigma = 1.0) {
  cv::Mat noise(rows, cols, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  if (blur_sigma > 0) cv::GaussianBlur(noise, noise, cv::Size(0, 0), blur_sigma);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  return noise;
}

// Shift by a (possibly fractional) number of pixels: out(x) = in(x - dx).
cv::Mat shifted(const cv::Mat& in, double dx) {
  cv::Mat out;
  const cv::Matx23d m(1, 0, dx, 0, 1, 0);
  cv::warpAffine(in, out, m, in.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return out;
}

// ---- reference: direct transcription of the definitions, int arithmetic ----
std::vector<uint32_t> referenceCensus(const cv::Mat& img, int ww, int wh) {
  // center-symmetric: pairs (o, -o) for the offsets o before the centre, row-major
  std::vector<uint32_t> out(img.total(), 0);
  const int rw = ww / 2, rh = wh / 2;
  for (int y = rh; y < img.rows - rh; ++y)
    for (int x = rw; x < img.cols - rw; ++x) {
      uint32_t bits = 0;
      for (int i = 0; i < (ww * wh) / 2; ++i) {
        const int dy = i / ww - rh, dx = i % ww - rw;
        bits = bits * 2 + (img.at<uint8_t>(y + dy, x + dx) < img.at<uint8_t>(y - dy, x - dx) ? 1 : 0);
      }
      out[y * img.cols + x] = bits;
    }
  return out;
}

cv::Mat referenceSgm(const cv::Mat& left, const cv::Mat& right, const Params& p) {
  const int H = left.rows, W = left.cols, D = p.num_disparities;
  // rows from the road band down take the road window's codes
  const int road_row = p.road_census_from >= 1.0 ? H : static_cast<int>(std::lround(p.road_census_from * H));
  auto census = [&](const cv::Mat& img) {
    auto codes = referenceCensus(img, p.census_width, p.census_height);
    const auto road = referenceCensus(img, p.road_census_width, p.road_census_height);
    for (int y = road_row; y < H; ++y)
      std::copy(road.begin() + static_cast<long>(y) * W, road.begin() + static_cast<long>(y + 1) * W,
                codes.begin() + static_cast<long>(y) * W);
    return codes;
  };
  const auto cl = census(left);
  const auto cr = census(right);
  auto at = [&](int y, int x, int d) { return (static_cast<size_t>(y) * W + x) * D + d; };
  std::vector<int> C(static_cast<size_t>(H) * W * D);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int d = 0; d < D; ++d) {
        const int xr = std::max(0, x - p.min_disparity - d);
        C[at(y, x, d)] = __builtin_popcount(cl[y * W + x] ^ cr[y * W + xr]);
      }
  const int dirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};  // (dx, dy): ->, <-, down, up
  std::vector<std::vector<int>> paths;
  for (const auto& dir : dirs) {
    std::vector<int> L(C.size());
    const int dx = dir[0], dy = dir[1];
    // visit pixels so that p - r is always done before p
    for (int i = 0; i < H; ++i)
      for (int j = 0; j < W; ++j) {
        const int y = dy >= 0 ? i : H - 1 - i;
        const int x = dx >= 0 ? j : W - 1 - j;
        const int px = x - dx, py = y - dy;
        const bool start = px < 0 || px >= W || py < 0 || py >= H;
        int prev_min = 1 << 30;
        if (!start)
          for (int d = 0; d < D; ++d) prev_min = std::min(prev_min, L[at(py, px, d)]);
        for (int d = 0; d < D; ++d) {
          int v = C[at(y, x, d)];
          if (!start) {
            int m = std::min(L[at(py, px, d)], prev_min + p.sgm_p2);
            if (d > 0) m = std::min(m, L[at(py, px, d - 1)] + p.sgm_p1);
            if (d + 1 < D) m = std::min(m, L[at(py, px, d + 1)] + p.sgm_p1);
            v += m - prev_min;
          }
          L[at(y, x, d)] = v;
        }
      }
    paths.push_back(std::move(L));
  }
  // winners work on the rounded average avg(avg(->, <-), avg(down, up))
  auto avg = [](int a, int b) { return (a + b + 1) / 2; };
  std::vector<int> S(C.size());
  for (size_t k = 0; k < S.size(); ++k)
    S[k] = avg(avg(paths[0][k], paths[1][k]), avg(paths[2][k], paths[3][k]));
  cv::Mat disparity(H, W, CV_32FC1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      int best = 0;
      for (int d = 1; d < D; ++d)
        if (S[at(y, x, d)] < S[at(y, x, best)]) best = d;
      disparity.at<float>(y, x) = static_cast<float>(best + p.min_disparity);
    }
  // no census within half a window of the border: no measurement there
  const int rw = (road_row < H ? std::max(p.census_width, p.road_census_width) : p.census_width) / 2;
  const int top = p.census_height / 2, bottom = p.census_height / 2;  // the main window's band, also under the road window
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (y < top || y >= H - bottom || x < rw || x >= W - rw) disparity.at<float>(y, x) = 0.0f;
  return disparity;
}

Params plainParams(int D, int min_disparity) {
  Params p;
  p.algorithm = "nerv_sgm";
  p.num_disparities = D;
  p.min_disparity = min_disparity;
  p.subpixel = false;
  p.uniqueness_ratio = 0;
  p.lr_max_diff = -1;
  p.speckle_window_size = 0;
  p.threads = 2;
  return p;
}

// A scene with a foreground square over a background: right(x) is the scene,
// left(x) = right(x - d) with d = fg_disp on the square and bg_disp elsewhere.
struct OcclusionScene {
  cv::Mat left, right;
  int square_x = 60, square_w = 40, y0 = 20, y1 = 76, fg = 20, bg = 8;
};
OcclusionScene occlusionScene() {
  OcclusionScene s;
  const int rows = 96, cols = 160;
  const cv::Mat bg = texture(rows, cols + 64, 11, 1.0), fg = texture(rows, cols + 64, 12, 1.0);
  s.right.create(rows, cols, CV_8UC1);
  s.left.create(rows, cols, CV_8UC1);
  auto inSquare = [&](int y, int xr) { return y >= s.y0 && y < s.y1 && xr >= s.square_x && xr < s.square_x + s.square_w; };
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) {
      s.right.at<uint8_t>(y, x) = inSquare(y, x) ? fg.at<uint8_t>(y, x + 32) : bg.at<uint8_t>(y, x + 32);
      const int xf = x - s.fg;  // right pixel if this left pixel is on the square
      s.left.at<uint8_t>(y, x) = inSquare(y, xf) ? fg.at<uint8_t>(y, xf + 32)
                                                 : bg.at<uint8_t>(y, x - s.bg + 32);
    }
  return s;
}

}  // namespace

TEST(stereoSgm, CensusMatchesReference) {
  const cv::Mat img = texture(30, 41, 1, 0.0);
  cv::Mat census;
  censusTransform(img, 9, 7, census);
  const auto ref = referenceCensus(img, 9, 7);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) ASSERT_EQ(census.ptr<uint32_t>(y)[x], ref[y * img.cols + x]) << x << "," << y;
}

TEST(stereoSgm, MatchesReferenceIntegerDisparities) {
  // D = 32 runs the AVX2 path (where built), D = 48 the scalar fallback; min_disparity shifts.
  // road_census_from 0.6: rows 24.. use the flat road window; 1: one window everywhere.
  for (const auto& [D, min_d, road_from] :
       std::vector<std::tuple<int, int, double>>{{32, 0, 0.6}, {48, 3, 0.6}, {64, 5, 1.0}, {32, 0, 1.0}}) {
    const cv::Mat right = texture(40, 96, 2, 1.2);
    const cv::Mat left = shifted(right, 9.0);
    Params p = plainParams(D, min_d);
    p.road_census_from = road_from;
    cv::Mat disparity;
    createOwnSgm(p)->compute(left, right, disparity);
    cv::Mat expected = referenceSgm(left, right, p);
    expected.setTo(0.0f, expected <= 0.0f);  // nerv encodes disparity 0 as invalid
    expected = referenceMedianFill(expected);
    ASSERT_EQ(cv::countNonZero(disparity != expected), 0) << "D " << D << " min " << min_d << " road " << road_from;
    EXPECT_GT(cv::countNonZero(disparity == 9.0f), disparity.total() / 2);  // not vacuous
  }
}

TEST(stereoSgm, HalfSplitMatchesReferenceOnFewAndOddRows) {
  // Each vertical path runs over one half of the rows, kept every k rows,
  // and is continued over the other half from the saved edge row; pass 3
  // recomputes it per k-row segment from the checkpoint before it: heights
  // where a half has no row, one row, or one row more than the other, halves
  // and last segments shorter than k, and several segment boundaries (37 and
  // 70 rows with k = 3). A 15x1 census leaves no border rows, so the rows
  // where the paths start and meet are compared too; 9x7 (the default) with
  // the road band checks odd heights.
  struct Case { int census_width, census_height, road_census_height; };
  for (const Case& c : {Case{15, 1, 1}, Case{9, 7, 3}})
    for (const int rows : {1, 2, 3, 4, 5, 9, 10, 11, 37, 70})
      for (const int segment_rows : {kSgmSegmentRows, 3})
        for (const int D : {32, 48})  // AVX2 path (where built) and scalar fallback
          for (const bool simd : {true, false})
            for (const int threads : {1, 2}) {
              const cv::Mat right = texture(rows, 96, 5, 1.2);
              const cv::Mat left = shifted(right, 9.0);
              Params p = plainParams(D, 2);
              p.census_width = c.census_width;
              p.census_height = c.census_height;
              p.road_census_height = c.road_census_height;
              p.road_census_from = 0.6;
              p.threads = threads;
              cv::Mat disparity;
              createOwnSgm(p, simd, segment_rows)->compute(left, right, disparity);
              cv::Mat expected = referenceSgm(left, right, p);
              expected.setTo(0.0f, expected <= 0.0f);
              expected = referenceMedianFill(expected);
              ASSERT_EQ(disparity.size(), left.size());
              ASSERT_EQ(cv::countNonZero(disparity != expected), 0)
                  << "rows " << rows << " k " << segment_rows << " census height " << c.census_height << " D " << D
                  << " simd " << simd << " threads " << threads;
              if (c.census_height == 1 && rows >= 3) {  // not vacuous
                EXPECT_GT(cv::countNonZero(disparity == 9.0f), disparity.total() / 2) << "rows " << rows;
              }
            }
}

// A service keeps one matcher for every frame; a calibration change brings
// another size. Every buffer (checkpoints, edge rows, segment and row
// workspaces) must follow: the reused matcher gives what a fresh one gives.
TEST(stereoSgm, OneMatcherReusedAcrossImageSizesEqualsFreshOnes) {
  Params p = plainParams(32, 2);
  p.threads = 2;
  p.subpixel = true;
  p.uniqueness_ratio = 10;
  const auto reused = createOwnSgm(p, true, 3);
  struct Size2 { int rows, cols; };
  int compared = 0;
  for (const Size2 s : {Size2{70, 96}, Size2{9, 96}, Size2{37, 60}, Size2{1, 40}, Size2{70, 128}, Size2{70, 96}}) {
    const cv::Mat right = texture(s.rows, s.cols, 5 + s.rows % 3, 1.2);
    const cv::Mat left = shifted(right, 7.0);
    cv::Mat a, ca, b, cb;
    reused->compute(left, right, a, ca);
    createOwnSgm(p, true, 3)->compute(left, right, b, cb);
    ASSERT_EQ(a.size(), left.size());
    ASSERT_EQ(cv::countNonZero(a != b), 0) << s.rows << "x" << s.cols;
    ASSERT_EQ(cv::countNonZero(ca != cb), 0) << s.rows << "x" << s.cols;
    compared += cv::countNonZero(a > 0);
  }
  EXPECT_GT(compared, 5000) << "the matcher hardly found any disparity: the comparison proves little";
}

TEST(stereoSgm, PathStepSimdEqualsScalar) {
  if (!pathSimdAvailable()) GTEST_SKIP() << "built without a vector path step (no AVX2, NEON or SSE4.1)";
  std::mt19937 rng(7);
  // Register-multiple lengths, with and without a 64-byte multiple; 16 and 48 take the 16-byte
  // step (SSE4.1 or NEON) on every build that has one, an AVX2 build included.
  for (const int D : {16, 48, 64, 96, 128}) {
  std::vector<uint8_t> cost(D), prev(D), a(D), b(D);
  for (int trial = 0; trial < 2000; ++trial) {
    const PathPenalties pen{static_cast<int>(rng() % 20), 0};
    PathPenalties q = pen;
    q.p2 = pen.p1 + 1 + static_cast<int>(rng() % (255 - 32 - pen.p1));
    for (auto& c : cost) c = rng() % 33;
    for (auto& v : prev) v = rng() % (33 + q.p2);  // any reachable path value, up to max C + P2
    const uint8_t prev_min = *std::min_element(prev.begin(), prev.end());
    const uint8_t ma = pathStepScalar(cost.data(), prev.data(), prev_min, a.data(), D, q);
    const uint8_t mb = pathStepSimd(cost.data(), prev.data(), prev_min, b.data(), D, q);
    ASSERT_EQ(a, b) << "D " << D;
    ASSERT_EQ(ma, mb) << "D " << D;
  }
  }
}

// The cost loops for other targets give the plain loop's bytes: AVX2 (targets without
// AVX-512 VPOPCNTDQ), SSE4.1 (without AVX2) and NEON (ARM), each where this build has it;
// any 32-bit codes (not only 31-bit census), D a multiple of 32 or 16 or neither,
// min_disparity > 0, a column range that does not start at 0. So does the dispatcher.
TEST(stereoSgm, CensusCostSimdEqualsScalar) {
  std::vector<std::pair<const char*, CensusCostLoop>> loops = {{"dispatch", censusCostRange}};
#if defined(__AVX2__)
  loops.push_back({"AVX2", censusCostRangeAvx2});
#endif
#if defined(__SSE4_1__)
  loops.push_back({"SSE4.1", censusCostRangeSse41});
#endif
#if defined(__ARM_NEON)
  loops.push_back({"NEON", censusCostRangeNeon});
#endif
  std::mt19937 rng(7);
  const int cols = 97;
  for (const int D : {32, 64, 128, 16, 40, 7}) {
    for (const int min_d : {0, 3}) {
      std::vector<uint32_t> left(cols), right(cols), reversed(cols + min_d + D);
      for (auto& v : left) v = rng();
      for (auto& v : right) v = rng();
      left[10] = 0xffffffffu;  // against the zero padding below: 32 ones, the largest count
      right[0] = 0;
      reverseCensusRow(right.data(), cols, min_d, D, reversed.data());
      const int x0 = 9, x1 = cols;
      std::vector<uint8_t> a((x1 - x0) * D);
      censusCostRangeScalar(left.data(), reversed.data(), cols, x0, x1, min_d, D, a.data());
      if (min_d == 0 && D == 128) {
        EXPECT_EQ(a[(10 - x0) * D + D - 1], 32);  // x - D < 0: the padding, right[0]
      }
      for (const auto& [name, loop] : loops) {
        std::vector<uint8_t> b((x1 - x0) * D, 0xee);
        loop(left.data(), reversed.data(), cols, x0, x1, min_d, D, b.data());
        ASSERT_EQ(a, b) << name << ", D " << D << " min_disparity " << min_d;
      }
    }
  }
}

// The start line names the code this build runs (a slow matcher on a CPU without AVX2
// says why in its first line).
TEST(stereoSgm, CodePathsNameTheBuild) {
  const std::string paths = ownSgmCodePaths();
#if defined(__AVX2__)
  EXPECT_NE(paths.find("path steps and winners AVX2, "), std::string::npos) << paths;
#elif defined(__SSE4_1__) || defined(__ARM_NEON)
  EXPECT_NE(paths.find(std::string("path steps and winners ") + pathStepPath() + " (no AVX2), "),
            std::string::npos) << paths;
#else
  EXPECT_NE(paths.find("path steps and winners portable loops (no AVX2), "), std::string::npos) << paths;
#endif
  EXPECT_EQ(std::string(winnerPath()), pathStepPath());
  EXPECT_NE(paths.find(std::string("census costs ") + censusCostPath()), std::string::npos) << paths;
}

TEST(stereoSgm, SimdMatcherEqualsScalarMatcher) {
  const OcclusionScene s = occlusionScene();
  Params p;
  p.num_disparities = 64;
  cv::Mat d_simd, c_simd, d_scalar, c_scalar;
  createOwnSgm(p, true)->compute(s.left, s.right, d_simd, c_simd);
  createOwnSgm(p, false)->compute(s.left, s.right, d_scalar, c_scalar);
  EXPECT_EQ(cv::countNonZero(d_simd != d_scalar), 0);
  EXPECT_EQ(cv::countNonZero(c_simd != c_scalar), 0);
  EXPECT_GT(cv::countNonZero(d_simd), d_simd.total() / 2);
}

TEST(stereoSgm, ThreadsDoNotChangeTheResult) {
  const OcclusionScene s = occlusionScene();
  Params p;
  p.num_disparities = 64;
  p.threads = 1;
  cv::Mat one, two;
  createOwnSgm(p)->compute(s.left, s.right, one);
  p.threads = 2;
  createOwnSgm(p)->compute(s.left, s.right, two);
  EXPECT_EQ(cv::countNonZero(one != two), 0);
}

TEST(stereoSgm, ShiftedTextureRecoversConstantDisparity) {
  // Integer shifts come back exact; fractional ones within 0.25 px at the median
  // (the equiangular fit on the aggregated cost keeps a bias of up to ~0.2 px
  // toward integers, see docs/stereo.md).
  for (double truth : {10.0, 17.0, 10.5, 13.25}) {
    const cv::Mat base = texture(80, 200, 3, 1.5);
    const cv::Mat left = shifted(base, truth / 2), right = shifted(base, -truth / 2);
    Params p;
    p.num_disparities = 32;
    cv::Mat disparity, confidence;
    StereoMatcher::create(p)->compute(left, right, disparity, confidence);
    const cv::Rect interior(40, 8, 150, 64);  // away from borders and the left strip with no match
    const cv::Mat d = disparity(interior);
    std::vector<float> values;
    int close = 0, near = 0;
    for (int y = 0; y < d.rows; ++y)
      for (int x = 0; x < d.cols; ++x)
        if (d.at<float>(y, x) > 0) {
          values.push_back(d.at<float>(y, x));
          close += std::abs(d.at<float>(y, x) - truth) <= 0.25;
          near += std::abs(d.at<float>(y, x) - truth) <= 0.5;
        }
    ASSERT_GT(values.size(), 0.9 * d.total()) << truth;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    EXPECT_NEAR(values[values.size() / 2], truth, 0.25) << "median disparity";
    if (truth == std::floor(truth))
      EXPECT_GT(close, 0.95 * values.size()) << "disparity " << truth << " within 0.25 px";
    else
      EXPECT_GT(near, 0.9 * values.size()) << "disparity " << truth << " within 0.5 px";
    // confidence: within 0..1, zero exactly where invalid
    double lo, hi;
    cv::minMaxLoc(confidence, &lo, &hi);
    EXPECT_GE(lo, 0.0);
    EXPECT_LE(hi, 1.0);
    EXPECT_EQ(cv::countNonZero((confidence > 0) != (disparity > 0)), 0);
  }
}

TEST(stereoSgm, SaturatedPatchesGiveNoDisparity) {
  // Glare over the same pixels of both views: a flat white block matches itself at
  // its edges (disparity ~0, "far away") and the paths carry values into it. With
  // flat_census_invalid (default) nothing inside it is measured; a flat dark block is
  // left to the matcher, and the textured rest is as without the rule.
  const cv::Mat base = texture(120, 320, 5, 1.2);
  cv::Mat left = shifted(base, 6.0), right = shifted(base, -6.0);  // 12 px everywhere
  const cv::Rect glare(100, 30, 120, 60), dark(20, 30, 50, 60);
  left(glare).setTo(255);
  right(glare).setTo(255);
  left(dark).setTo(3);
  right(dark).setTo(3);
  Params on, off;
  on.num_disparities = off.num_disparities = 32;
  off.flat_census_invalid = false;
  ASSERT_TRUE(on.flat_census_invalid);
  cv::Mat d_on, d_off;
  StereoMatcher::create(on)->compute(left, right, d_on);
  StereoMatcher::create(off)->compute(left, right, d_off);
  const cv::Rect inside(glare.x + 5, glare.y + 4, glare.width - 10, glare.height - 8);
  EXPECT_EQ(cv::countNonZero(d_on(inside)), 0);
  EXPECT_GT(cv::countNonZero(d_off(inside)), inside.area() / 20) << "the case the rule is for";
  EXPECT_EQ(cv::countNonZero(d_on(dark) != d_off(dark)), 0);
  cv::Mat outside = cv::Mat::ones(left.size(), CV_8U);
  outside(cv::Rect(glare.x - 8, glare.y - 8, glare.width + 16, glare.height + 16)).setTo(0);
  const int differ = cv::countNonZero((d_on != d_off) & outside);
  EXPECT_LT(differ, cv::countNonZero(outside) / 100);
  // The cache key tells the two apart.
  EXPECT_NE(describeParams(on), describeParams(off));
}

TEST(stereoSgm, LeftRightCheckInvalidatesOccludedStrip) {
  const OcclusionScene s = occlusionScene();
  Params p;
  p.num_disparities = 32;
  p.speckle_window_size = 0;
  p.boundary_snap_px = 0;  // the left-right check alone
  cv::Mat checked, unchecked;
  StereoMatcher::create(p)->compute(s.left, s.right, checked);
  p.lr_max_diff = -1;
  p.uniqueness_ratio = 0;
  StereoMatcher::create(p)->compute(s.left, s.right, unchecked);
  // occluded in the right view: left x in [square_x + bg, square_x + fg), rows of the square
  const cv::Rect strip(s.square_x + s.bg + 1, s.y0 + 4, s.fg - s.bg - 2, s.y1 - s.y0 - 8);
  const double invalid_checked = 1.0 - cv::countNonZero(checked(strip)) / double(strip.area());
  const double invalid_unchecked = 1.0 - cv::countNonZero(unchecked(strip)) / double(strip.area());
  EXPECT_GT(invalid_checked, 0.8);
  EXPECT_LT(invalid_unchecked, 0.2);
  // visible surfaces keep their disparity
  const cv::Rect fg(s.square_x + s.fg + 4, s.y0 + 4, s.square_w - 8, s.y1 - s.y0 - 8);
  const cv::Rect bg(s.square_x + s.fg + s.square_w + 6, 8, 30, 80);
  EXPECT_GT(cv::countNonZero(cv::abs(checked(fg) - s.fg) <= 1.0), 0.9 * fg.area());
  EXPECT_GT(cv::countNonZero(cv::abs(checked(bg) - s.bg) <= 1.0), 0.9 * bg.area());
}

TEST(stereoSgm, EveryAlgorithmRunsAndReducedResolutionKeepsSize) {
  const OcclusionScene s = occlusionScene();
  for (const char* name : {"nerv_sgm", "sgbm", "sgbm_full", "sgbm_wls", "bm"}) {
    for (int downscale : {1, 2}) {
      Params p;
      p.algorithm = name;
      p.num_disparities = 64;
      p.downscale = downscale;
      cv::Mat disparity, confidence;
      auto m = StereoMatcher::create(p);
      m->compute(s.left, s.right, disparity, confidence);
      ASSERT_EQ(disparity.size(), s.left.size()) << name;
      ASSERT_EQ(confidence.size(), s.left.size()) << name;
      ASSERT_EQ(disparity.type(), CV_32FC1);
      const cv::Rect bg(s.square_x + s.fg + s.square_w + 6, 8, 30, 80);
      EXPECT_GT(cv::countNonZero(cv::abs(disparity(bg) - s.bg) <= 1.5), 0.6 * bg.area())
          << name << " downscale " << downscale;
    }
  }
}

TEST(stereoSgm, FusedWinnersEqualSeparateSteps) {
  // random path costs with many ties; every D the fused loops take (the 16-byte one, which
  // an AVX2 build runs only for D = 16, 48, ..., on its own as well), min_disparity > 0
  std::mt19937 rng(3);
  int fused16 = 0;
  for (int D : {16, 32, 48, 96, 128, 240}) {
    const int cols = 300;
    std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(static_cast<size_t>(cols) * D));
    for (auto& r : rows)
      for (auto& v : r) v = static_cast<uint8_t>(40 + rng() % 24);
    const uint8_t* const paths[4] = {rows[0].data(), rows[1].data(), rows[2].data(), rows[3].data()};
    WinnerOptions opt;
    opt.uniqueness_ratio = 3;
    std::vector<int16_t> best_a(cols), best_b(cols), right_a(cols), right_b(cols);
    std::vector<float> disp_a(cols), disp_b(cols), conf_a(cols), conf_b(cols);
    std::vector<uint8_t> sum, cost;
    std::vector<int16_t> index;
    selectWinnersFromPaths(paths, cols, D, 5, opt, best_a.data(), disp_a.data(), conf_a.data(),
                           right_a.data(), sum, cost, index);
    sum.resize(static_cast<size_t>(cols) * D);
    averagePaths(paths, sum.size(), sum.data());
    selectLeftWinners(sum.data(), cols, D, opt, best_b.data(), disp_b.data(), conf_b.data());
    selectRightWinners(sum.data(), cols, D, 5, right_b.data(), cost, index);
    refineSubpixel(paths, cols, D, best_b.data(), disp_b.data());
    EXPECT_EQ(best_a, best_b) << D;
    EXPECT_EQ(right_a, right_b) << D;
    EXPECT_EQ(disp_a, disp_b) << D;
    EXPECT_EQ(conf_a, conf_b) << D;
    std::vector<int16_t> best_c(cols, 7), right_c(cols, 7);
    std::vector<float> disp_c(cols), conf_c(cols);
    if (selectWinnersFromPaths16(paths, cols, D, 5, opt, best_c.data(), disp_c.data(), conf_c.data(),
                                 right_c.data())) {
      EXPECT_EQ(best_c, best_b) << "16-byte loop, D " << D;
      EXPECT_EQ(right_c, right_b) << "16-byte loop, D " << D;
      EXPECT_EQ(disp_c, disp_b) << "16-byte loop, D " << D;
      EXPECT_EQ(conf_c, conf_b) << "16-byte loop, D " << D;
      ++fused16;
    }
    EXPECT_GT(std::count(best_a.begin(), best_a.end(), -1), 0) << "uniqueness test exercised";
    EXPECT_GT(std::count_if(best_a.begin(), best_a.end(), [](int16_t b) { return b >= 0; }), 0);
  }
#if defined(__SSE4_1__) || defined(__ARM_NEON)
  EXPECT_EQ(fused16, 6) << "the 16-byte loop ran on every D";
#endif
}

// Integral-image normals against slow references (naive cross products and
// brute-force box means), local vs full-frame, invalid input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ground_samples.hpp"
#include "integral_normals.hpp"
#include "local_fields.hpp"
#include "local_normals.hpp"
#include "naive_normals.hpp"
#include "point_cloud.hpp"
#include "snv_test_scenes.hpp"

namespace nerv::snv {
namespace {

// atan2 of |a x b| and a . b in double: acos of a float dot product cannot
// resolve angles below ~0.03 deg.
double angleDeg(const cv::Vec3f& a, const cv::Vec3f& b) {
  const cv::Vec3d ad(a), bd(b);
  return std::atan2(cv::norm(ad.cross(bd)), ad.dot(bd)) * 180.0 / CV_PI;
}

bool finiteVec(const cv::Vec3f& n) { return std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]); }

// A gently curved wall 8..12 m ahead: Z(u,v) = 10 + 1.5 sin(u/150) + 0.8 cos(v/90).
cv::Mat smoothSurface(const StereoCamera& c) {
  cv::Mat d(c.height, c.width, CV_32F);
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const double z = 10.0 + 1.5 * std::sin(u / 150.0) + 0.8 * std::cos(v / 90.0);
      d.at<float>(v, u) = static_cast<float>(c.fx * c.baseline_m / z);
    }
  return d;
}

TEST(snvPointCloud, MatchesStereoCameraAndMarksInvalid) {
  const StereoCamera c = test::kittiCamera();
  cv::Mat d(c.height, c.width, CV_32F, cv::Scalar(20.0f));
  d.at<float>(100, 200) = 0.0f;
  d.at<float>(101, 200) = -3.0f;
  const PointCloud pc = computePointCloud(d, c);
  const Point3 p = c.toPoint(300, 250, 20.0);
  EXPECT_NEAR(pc.x.at<float>(250, 300), p.x, 1e-4);
  EXPECT_NEAR(pc.y.at<float>(250, 300), p.y, 1e-4);
  EXPECT_NEAR(pc.z.at<float>(250, 300), p.z, 1e-4);
  EXPECT_TRUE(std::isnan(pc.z.at<float>(100, 200)));
  EXPECT_TRUE(std::isnan(pc.x.at<float>(101, 200)));
}

TEST(snvIntegralNormals, MatchNaiveCrossProductOnSmoothSurface) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat d = smoothSurface(c);
  IntegralNormalParams p;
  const NormalMap fast = computeNormalMap(d, c, p, 1);
  const NormalMap naive = computeNaiveNormalMap(d, c, 3, 1);
  double worst = 0;
  int compared = 0;
  for (int v = 20; v < c.height - 20; v += 3)
    for (int u = 20; u < c.width - 20; u += 3) {
      const cv::Vec3f a = fast.normals.at<cv::Vec3f>(v, u), b = naive.normals.at<cv::Vec3f>(v, u);
      ASSERT_TRUE(finiteVec(a)) << "no integral normal at " << u << "," << v;
      ASSERT_TRUE(finiteVec(b));
      worst = std::max(worst, angleDeg(a, b));
      ++compared;
    }
  std::printf("compared %d normals, worst angle %.4f deg\n", compared, worst);
  EXPECT_GT(compared, 40000);
  EXPECT_LT(worst, 1.0);
}

TEST(snvIntegralNormals, EqualBruteForceBoxMeans) {
  const StereoCamera c = test::kittiCamera();
  cv::Mat d = smoothSurface(c);
  cv::Mat noise(d.size(), CV_32F);
  cv::randn(noise, 0.0, 0.3);
  d += noise;
  for (bool smooth_disparity : {true, false}) {
    IntegralNormalParams p;
    p.smooth_disparity = smooth_disparity;
    IntegralNormalField field;
    field.prepare(d, c, p);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> ur(20, c.width - 21), vr(20, c.height - 21), rr(1, 4);
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
      const int u = ur(rng), v = vr(rng), r = rr(rng);
      cv::Vec3f a, b;
      ASSERT_TRUE(field.normalAt(u, v, r, a));
      ASSERT_TRUE(bruteForceSmoothedNormal(d, c, p, u, v, r, b));
      worst = std::max(worst, angleDeg(a, b));
    }
    EXPECT_LT(worst, 0.01) << "smooth_disparity=" << smooth_disparity;
  }
}

TEST(snvIntegralNormals, ExactOnPlanesAndFacingTheCamera) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat d = test::roadDisparity(c, 1.5, -0.7, 1.65);
  const cv::Vec3d truth = test::roadNormal(1.5, -0.7);
  const NormalMap map = computeNormalMap(d, c, IntegralNormalParams{}, 2);
  int n = 0;
  double worst = 0;
  for (int j = 0; j < map.normals.rows; ++j)
    for (int i = 0; i < map.normals.cols; ++i) {
      const cv::Vec3f a = map.normals.at<cv::Vec3f>(j, i);
      if (!finiteVec(a)) continue;
      worst = std::max(worst, angleDeg(a, cv::Vec3f(truth)));
      ++n;
    }
  EXPECT_GT(n, 40000);
  EXPECT_LT(worst, 0.02);
}

TEST(snvIntegralNormals, WindowsStayOffDiscontinuities) {
  const StereoCamera c = test::kittiCamera();
  cv::Mat d = test::roadDisparity(c, 0.0, 0.0, 1.65);
  // A wall facing the camera 15 m ahead over the middle of the image.
  test::paintUprightFace(d, c, cv::Rect(500, 60, 200, 150), 15.0, 0.0);
  const NormalMap map = computeNormalMap(d, c, IntegralNormalParams{}, 1);
  // Right next to the wall's bottom edge both sides keep their own normal.
  const cv::Vec3f wall = map.normals.at<cv::Vec3f>(205, 600);
  const cv::Vec3f road = map.normals.at<cv::Vec3f>(216, 600);
  ASSERT_TRUE(finiteVec(wall));
  ASSERT_TRUE(finiteVec(road));
  EXPECT_LT(angleDeg(wall, cv::Vec3f(0, 0, -1)), 0.05);
  EXPECT_LT(angleDeg(road, cv::Vec3f(0, -1, 0)), 0.05);
  // On the edge itself there is no normal.
  EXPECT_FALSE(finiteVec(map.normals.at<cv::Vec3f>(209, 600)));
}

TEST(snvIntegralNormals, AnyIntervalIsTheSubsampledFullMap) {
  const StereoCamera c = test::kittiCamera();
  cv::Mat d = test::roadDisparity(c, 0.8, 0.3, 1.6);
  test::paintUprightFace(d, c, cv::Rect(300, 80, 120, 120), 12.0, 35.0);
  const NormalMap full = computeNormalMap(d, c, IntegralNormalParams{}, 1);
  for (int k = 2; k <= 6; ++k) {
    const NormalMap sub = computeNormalMap(d, c, IntegralNormalParams{}, k);
    ASSERT_EQ(sub.normals.rows, (c.height + k - 1) / k);
    ASSERT_EQ(sub.normals.cols, (c.width + k - 1) / k);
    int mismatches = 0;
    for (int j = 0; j < sub.normals.rows; ++j)
      for (int i = 0; i < sub.normals.cols; ++i) {
        const cv::Vec3f a = sub.normals.at<cv::Vec3f>(j, i), b = full.normals.at<cv::Vec3f>(j * k, i * k);
        if (finiteVec(a) != finiteVec(b) || (finiteVec(a) && angleDeg(a, b) > 1e-3)) ++mismatches;
      }
    EXPECT_EQ(mismatches, 0) << "interval " << k;
  }
}

TEST(snvLocalNormals, EqualTheFullMapInsideABand) {
  const StereoCamera c = test::kittiCamera();
  cv::Mat d = test::roadDisparity(c, 0.5, 0.0, 1.65);
  test::paintUprightFace(d, c, cv::Rect(700, 90, 90, 110), 14.0, -20.0);
  cv::Mat noise(d.size(), CV_32F);
  cv::randn(noise, 0.0, 0.1);
  cv::Mat noisy = d + noise;
  noisy.setTo(0.0f, d <= 0.0f);
  const int interval = 4;
  const NormalMap full = computeNormalMap(noisy, c, IntegralNormalParams{}, interval);
  const cv::Rect roi(690, 80, 120, 140);
  const cv::Range band = rowBandFor({roi}, c.height, IntegralNormalParams{}.max_radius_px);
  IntegralNormalField field;
  field.prepare(noisy, c, IntegralNormalParams{}, band.start, band.end);
  std::vector<LocalNormal> local;
  const int samples = localNormalsInRect(field, roi, interval, local);
  EXPECT_EQ(samples, (120 / 4) * (140 / 4));
  ASSERT_GT(local.size(), 500u);
  int full_count = 0;
  for (int v = 80; v < 220; v += interval)
    for (int u = 692; u < 810; u += interval)
      if (finiteVec(full.normals.at<cv::Vec3f>(v / interval, u / interval))) ++full_count;
  EXPECT_EQ(static_cast<int>(local.size()), full_count);
  for (const LocalNormal& ln : local) {
    const cv::Vec3f b = full.normals.at<cv::Vec3f>(ln.v / interval, ln.u / interval);
    ASSERT_TRUE(finiteVec(b));
    ASSERT_LT(angleDeg(ln.n, b), 1e-3) << ln.u << "," << ln.v;
  }
}

TEST(snvIntegralNormals, AllInvalidDisparityGivesNoNormals) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat d(c.height, c.width, CV_32F, cv::Scalar(0.0f));
  const NormalMap map = computeNormalMap(d, c, IntegralNormalParams{}, 1);
  EXPECT_EQ(cv::countNonZero(map.normals.reshape(1) == map.normals.reshape(1)), 0);  // all NaN
  IntegralNormalField field;
  field.prepare(d, c, IntegralNormalParams{});
  std::vector<LocalNormal> local;
  EXPECT_EQ(localNormalsInRect(field, cv::Rect(10, 10, 50, 50), 4, local), 12 * 12);
  EXPECT_TRUE(local.empty());
}

}  // namespace
}  // namespace nerv::snv

namespace nerv::snv {
namespace {

// The adaptive radius read from the edge integral equals the brief's
// definition r = min((B-1)/2, T/2) with B = cv::distanceTransform(DIST_C) of the edge map.
TEST(snvIntegralNormals, AdaptiveRadiusEqualsDistanceTransformDefinition) {
  const StereoCamera c = test::kittiCamera();
  cv::Mat d = test::roadDisparity(c, 0.4, 0.2, 1.65);
  test::paintUprightFace(d, c, cv::Rect(500, 60, 200, 150), 15.0, 20.0);
  test::paintUprightFace(d, c, cv::Rect(100, 120, 60, 120), 8.0, -40.0);
  d(cv::Rect(900, 250, 30, 30)).setTo(0.0f);  // a hole
  IntegralNormalField field;
  field.prepare(d, c, IntegralNormalParams{});
  const cv::Mat b = field.edgeDistance();
  int differ = 0, with_normal = 0;
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const int rb = (static_cast<int>(b.at<float>(v, u)) - 1) / 2;
      const int expected = std::max(0, std::min(rb, field.depthRadius(u, v)));
      const int r = field.adaptiveRadius(u, v);
      differ += r != expected;
      with_normal += r >= 1;
    }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(with_normal, 100000);
}

}  // namespace
}  // namespace nerv::snv

namespace nerv::snv {
namespace {

// A cluttered scene: tilted road, turned faces, a hole, noise, quantised to
// `step` px (1/16 = SGBM, 0 = not quantised).
cv::Mat clutteredScene(const StereoCamera& c, float step) {
  cv::Mat d = test::roadDisparity(c, 0.6, -0.4, 1.6);
  test::paintUprightFace(d, c, cv::Rect(500, 60, 200, 150), 15.0, 20.0);
  test::paintUprightFace(d, c, cv::Rect(100, 120, 60, 120), 8.0, -40.0);
  test::paintUprightFace(d, c, cv::Rect(1000, 40, 200, 200), 30.0, 0.0);
  cv::Mat noise(d.size(), CV_32F);
  cv::randn(noise, 0.0, 0.15);
  cv::Mat valid = d > 0.0f;
  cv::add(d, noise, d, valid);
  d(cv::Rect(900, 250, 30, 30)).setTo(0.0f);
  d(cv::Rect(0, 300, 5, 75)).setTo(0.0f);
  if (step > 0) {
    cv::Mat q = d / step;
    for (int v = 0; v < q.rows; ++v)
      for (int u = 0; u < q.cols; ++u) q.at<float>(v, u) = std::round(q.at<float>(v, u)) * step;
    d = q;
  }
  d.setTo(0.0f, d < 0.0f);
  return d;
}

// STYLE.md "each fast path against a slow reference": the vectorised row path
// (fixed-point or CV_64F integral, no per-pixel division) against the scalar
// per-pixel path, every interval: same pixels with a normal, same vectors
// within 1e-4 rad.
TEST(snvIntegralNormals, FastRowEqualsReference) {
  const StereoCamera c = test::kittiCamera();
  struct Variant {
    float step;
    bool smooth_disparity;
    bool fixed_point;
  };
  for (const Variant var : {Variant{1.0f / 16, true, true}, Variant{1.0f / 256, true, true},
                            Variant{0.0f, true, false}, Variant{1.0f / 16, false, false}}) {
    const cv::Mat d = clutteredScene(c, var.step);
    IntegralNormalParams p;
    p.smooth_disparity = var.smooth_disparity;
    IntegralNormalField field;
    field.prepare(d, c, p);
    EXPECT_EQ(field.fixedPoint(), var.fixed_point) << "step " << var.step;
    for (int k = 1; k <= 6; ++k) {
      const NormalMap fast = computeNormalMap(d, c, p, k);
      const NormalMap ref = computeNormalMapReference(d, c, p, k);
      int differ = 0, both = 0;
      double worst_rad = 0;
      for (int j = 0; j < ref.normals.rows; ++j)
        for (int i = 0; i < ref.normals.cols; ++i) {
          const cv::Vec3f a = fast.normals.at<cv::Vec3f>(j, i), b = ref.normals.at<cv::Vec3f>(j, i);
          if (finiteVec(a) != finiteVec(b)) {
            ++differ;
            continue;
          }
          if (!finiteVec(a)) continue;
          ++both;
          worst_rad = std::max(worst_rad, angleDeg(a, b) * CV_PI / 180.0);
        }
      SCOPED_TRACE(::testing::Message() << "step " << var.step << " smooth_disparity "
                                        << var.smooth_disparity << " interval " << k);
      EXPECT_EQ(differ, 0);
      EXPECT_GT(both, 200000 / (k * k));
      EXPECT_LT(worst_rad, 1e-4);
    }
  }
}

// Rows given by any start, count and step agree with the per-pixel path, also
// at the image borders and outside the band (no normal, no crash).
TEST(snvIntegralNormals, NormalRowAnyStartAndStep) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat d = clutteredScene(c, 1.0f / 16);
  IntegralNormalField field;
  field.prepare(d, c, IntegralNormalParams{}, 150, 330);
  NormalRow row;
  for (int v : {140, 150, 151, 160, 200, 313, 329, 330}) {
    for (int step : {1, 3, 7}) {
      for (int u0 : {0, 1, 17, 1200}) {
        const int count = (c.width - 1 - u0) / step + 1;
        field.normalRow(v, u0, count, step, row);
        ASSERT_EQ(static_cast<int>(row.nx.size()), count);
        for (int i = 0; i < count; ++i) {
          const int u = u0 + i * step;
          const int r = field.adaptiveRadius(u, v);
          ASSERT_EQ(row.radius[i], r) << u << "," << v;
          cv::Vec3f n;
          const bool has = r >= 1 && field.normalAt(u, v, r, n);
          const cv::Vec3f a(row.nx[i], row.ny[i], row.nz[i]);
          ASSERT_EQ(finiteVec(a), has) << u << "," << v;
          if (has) {
            ASSERT_LT(angleDeg(a, n) * CV_PI / 180.0, 1e-4) << u << "," << v;
          }
        }
      }
    }
  }
}

// A rectangle field (a ROI with its margin, as snv_extrinsic prepares above the
// ground band) gives every pixel of the ROI the radius and normal of a whole-image
// field, bit for bit in fixed point and in CV_64F within rounding; pixels at its
// own sides follow the per-pixel path of the same field (its sides act as the
// border). Also at the image's sides, with one field reused across sizes.
TEST(snvIntegralNormals, RegionFieldEqualsWholeImageInsideTheRoi) {
  const StereoCamera c = test::kittiCamera();
  const int margin = 2 * IntegralNormalParams{}.max_radius_px + 1;
  IntegralNormalField region;
  for (const float step : {1.0f / 16, 0.0f}) {
    const cv::Mat d = clutteredScene(c, step);
    IntegralNormalField whole;
    whole.prepare(d, c, IntegralNormalParams{});
    const cv::Rect image(0, 0, c.width, c.height);
    for (const cv::Rect roi : {cv::Rect(480, 50, 240, 170), cv::Rect(0, 100, 170, 150), cv::Rect(1100, 0, 142, 90),
                               cv::Rect(910, 240, 40, 50), cv::Rect(600, 370, 30, 5)}) {
      const cv::Rect with_margin = cv::Rect(roi.x - margin, roi.y - margin, roi.width + 2 * margin,
                                            roi.height + 2 * margin) & image;
      region.prepare(d, c, IntegralNormalParams{}, with_margin);
      ASSERT_EQ(region.colBegin(), with_margin.x);
      ASSERT_EQ(region.colEnd(), with_margin.x + with_margin.width);
      ASSERT_EQ(region.fixedPoint(), step > 0);
      SCOPED_TRACE(::testing::Message() << "step " << step << " roi " << roi);
      NormalRow a, b;
      int with_normal = 0;
      for (int v = roi.y; v < roi.y + roi.height; ++v)
        for (int st : {1, 3}) {
          const int count = (roi.width - 1) / st + 1;
          region.normalRow(v, roi.x, count, st, a);
          whole.normalRow(v, roi.x, count, st, b);
          for (int i = 0; i < count; ++i) {
            ASSERT_EQ(a.radius[i], b.radius[i]) << roi.x + i * st << "," << v;
            ASSERT_EQ(std::isnan(a.nx[i]), std::isnan(b.nx[i]));
            if (std::isnan(a.nx[i])) continue;
            ++with_normal;
            const cv::Vec3f na(a.nx[i], a.ny[i], a.nz[i]), nb(b.nx[i], b.ny[i], b.nz[i]);
            if (step > 0)
              ASSERT_EQ(na, nb);
            else
              ASSERT_LT(angleDeg(na, nb), 1e-3);
          }
        }
      EXPECT_GT(with_normal, roi.area() / 4);
      // The region's own sides: the per-pixel path of the same field.
      for (int v : {with_margin.y, with_margin.y + 5, with_margin.y + with_margin.height - 1}) {
        const int count = with_margin.width;
        region.normalRow(v, with_margin.x, count, 1, a);
        for (int i = 0; i < count; ++i) ASSERT_EQ(a.radius[i], region.adaptiveRadius(with_margin.x + i, v));
      }
    }
  }
}

// LocalFields: a ROI inside the ground rows reads the ground field, any other
// (above it, straddling it, at the image's sides) gets its own; the local normals
// of every ROI equal those of one whole-image field, also when the same object is
// reused for a second frame with other ROIs, and empty / outside ROIs give none.
TEST(snvLocalFields, RoisOutsideTheGroundRowsGetTheirOwnFieldWithTheSameNormals) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat d = clutteredScene(c, 1.0f / 16);
  const GroundSampleParams gp;
  const cv::Range ground_rows = groundRows(c, GroundModel{}, gp);
  ASSERT_FALSE(ground_rows.empty());
  IntegralNormalField whole;
  whole.prepare(d, c, IntegralNormalParams{});
  LocalFields fields;
  const std::vector<std::vector<cv::Rect>> frames = {
      {cv::Rect(500, 60, 200, 150), cv::Rect(100, ground_rows.start + 5, 60, 40), cv::Rect(1000, 40, 200, 200),
       cv::Rect(0, 0, 40, 375), cv::Rect(), cv::Rect(1300, 10, 20, 20) & cv::Rect(0, 0, c.width, c.height)},
      {cv::Rect(300, ground_rows.start, 80, ground_rows.size()), cv::Rect(1180, 100, 62, 120)}};
  const std::vector<int> own_expected = {3, 1};
  for (size_t fi = 0; fi < frames.size(); ++fi) {
    const std::vector<cv::Rect>& rois = frames[fi];
    fields.prepare(d, c, IntegralNormalParams{}, ground_rows, rois);
    EXPECT_EQ(fields.ownFields(), own_expected[fi]);
    EXPECT_EQ(fields.ground().rowBegin(), std::max(0, ground_rows.start - 17));
    for (size_t i = 0; i < rois.size(); ++i) {
      SCOPED_TRACE(::testing::Message() << "frame " << fi << " roi " << rois[i]);
      std::vector<LocalNormal> a, b;
      const int na = localNormalsInRect(fields.roi(i), rois[i], 2, a);
      const int nb = localNormalsInRect(whole, rois[i], 2, b);
      EXPECT_EQ(na, nb);
      ASSERT_EQ(a.size(), b.size());
      for (size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(a[k].u, b[k].u);
        ASSERT_EQ(a[k].v, b[k].v);
        ASSERT_EQ(a[k].n, b[k].n);
      }
      if (rois[i].area() > 1000) {
        EXPECT_GT(a.size(), 100u);
      }
    }
  }
}

// The vectorised row prefix sums (8 lanes and a scalar tail) and the reused
// buffers against cv::integral of the same edge map and fixed-point values, on
// widths that are not multiples of 8, bands of different sizes, and a field
// reused across images of different sizes.
TEST(snvIntegralNormals, IntegralImagesEqualCvIntegral) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat full = clutteredScene(c, 1.0f / 16);
  IntegralNormalField reused;
  struct Case {
    int width, row0, row1, threads;  // threads: row chunks accumulated apart, then offset
  };
  const int threads_before = cv::getNumThreads();
  for (const Case k : {Case{c.width, 100, 330, 2}, Case{1237, 0, c.height, 2}, Case{13, 40, 90, 2},
                       Case{c.width - 3, 200, 375, 1}, Case{c.width, 150, 160, 2}, Case{c.width, 0, 375, 1}}) {
    cv::setNumThreads(k.threads);
    const cv::Mat d = full(cv::Rect(0, 0, k.width, c.height)).clone();
    StereoCamera ck = c;
    ck.width = k.width;
    reused.prepare(d, ck, IntegralNormalParams{}, k.row0, k.row1);
    IntegralNormalField fresh;
    fresh.prepare(d, ck, IntegralNormalParams{}, k.row0, k.row1);
    SCOPED_TRACE(::testing::Message() << "width " << k.width << " rows " << k.row0 << ".." << k.row1
                                      << " threads " << k.threads);
    ASSERT_TRUE(reused.fixedPoint());
    // Edge map rebuilt from the definition: invalid, or a jump to the right or below.
    const cv::Mat band = d.rowRange(k.row0, k.row1);
    cv::Mat edge(band.size(), CV_8U), fixed(band.size(), CV_64F);  // 256 * d, exact integers
    for (int y = 0; y < band.rows; ++y)
      for (int u = 0; u < band.cols; ++u) {
        const int v = y + k.row0;
        const float x = d.at<float>(v, u);
        const float right = u + 1 < d.cols ? d.at<float>(v, u + 1) : x;
        const float below = v + 1 < d.rows ? d.at<float>(v + 1, u) : x;
        const float thr = std::max(1.0f, 0.05f * x);
        const bool valid = x > 0.0f && x < 1e6f;
        edge.at<uchar>(y, u) = !valid || std::abs(right - x) > thr || std::abs(below - x) > thr;
        fixed.at<double>(y, u) = valid ? std::round(x * 256.0) : 0.0;
      }
    cv::Mat edge_ref, value_ref;
    cv::integral(edge, edge_ref, CV_32S);
    cv::integral(fixed, value_ref, CV_64F);
    for (const IntegralNormalField* f : {&reused, &fresh}) {
      ASSERT_EQ(f->edgeIntegral().size(), edge_ref.size());
      ASSERT_EQ(f->edgeIntegral().type(), CV_16U);
      int edge_differ = 0;  // the edge integral wraps modulo 2^16
      for (int y = 0; y < edge_ref.rows; ++y)
        for (int u = 0; u < edge_ref.cols; ++u)
          edge_differ += f->edgeIntegral().at<uint16_t>(y, u) != static_cast<uint16_t>(edge_ref.at<int>(y, u));
      EXPECT_EQ(edge_differ, 0);
      int differ = 0;
      for (int y = 0; y < value_ref.rows; ++y)
        for (int u = 0; u < value_ref.cols; ++u)
          differ += f->valueIntegral().at<uint32_t>(y, u) !=
                    static_cast<uint32_t>(static_cast<int64_t>(value_ref.at<double>(y, u)));
      EXPECT_EQ(differ, 0);
    }
  }
  cv::setNumThreads(threads_before);
}

// Ground samples of the row path (candidates tested a grid row at a time,
// normals over the candidates' span) against a per-pixel reference built from
// isGroundCandidate, adaptiveRadius and normalAt: same pixels, same points,
// normals within 1e-4 rad; with and without a ground model, intervals 1..5.
TEST(snvGroundSamples, RowPathEqualsPerPixelReference) {
  const StereoCamera c = test::kittiCamera();
  const cv::Mat d = clutteredScene(c, 1.0f / 16);
  const GroundModel model = test::roadModel(c, 0.6, -0.4, 1.6);  // the scene's road
  GroundSampleParams gp;
  const float min_up = static_cast<float>(std::cos(gp.prior_cone_deg * CV_PI / 180.0));
  for (const GroundModel& m : {GroundModel{}, model}) {
    const cv::Range rows = groundRows(c, m, gp);
    IntegralNormalField field;
    field.prepare(d, c, IntegralNormalParams{}, std::max(0, rows.start - 17), rows.end);
    for (int k = 1; k <= 5; ++k) {
      SCOPED_TRACE(::testing::Message() << "model " << m.valid << " interval " << k);
      const std::vector<GroundSample> fast = selectGroundSamples(field, d, c, m, gp, rows, k);
      std::vector<GroundSample> ref;
      for (int v = (rows.start + k - 1) / k * k; v < rows.end; v += k)
        for (int u = 0; u < c.width; u += k) {
          if (!isGroundCandidate(v, d.at<float>(v, u), c, m, gp)) continue;
          const int r = field.adaptiveRadius(u, v);
          cv::Vec3f n;
          if (r < 1 || !field.normalAt(u, v, r, n) || !(-n[1] >= min_up)) continue;
          GroundSample s;
          s.u = u;
          s.v = v;
          s.n = n;
          s.d = d.at<float>(v, u);
          const float z = static_cast<float>(c.fx * c.baseline_m) / s.d;
          s.p = cv::Vec3f(static_cast<float>((u - c.cx) / c.fx) * z, static_cast<float>((v - c.cy) / c.fy) * z, z);
          ref.push_back(s);
        }
      ASSERT_EQ(fast.size(), ref.size());
      EXPECT_GT(ref.size(), 20000u / (k * k));
      for (size_t i = 0; i < ref.size(); ++i) {
        ASSERT_EQ(fast[i].u, ref[i].u);
        ASSERT_EQ(fast[i].v, ref[i].v);
        ASSERT_EQ(fast[i].d, ref[i].d);
        ASSERT_EQ(fast[i].p, ref[i].p) << ref[i].u << "," << ref[i].v;
        ASSERT_LT(angleDeg(fast[i].n, ref[i].n) * CV_PI / 180.0, 1e-4);
      }
    }
  }
}

}  // namespace
}  // namespace nerv::snv

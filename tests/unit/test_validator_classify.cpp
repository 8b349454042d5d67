// Every verdict path of the validator on constructed normal statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <yaml-cpp/yaml.h>

#include "validator.hpp"

namespace nerv::validator {
namespace {

Hypothesis hyp(int id, float height_m = 1.5f, float width_m = 1.8f) {
  Hypothesis h;
  h.id = id;
  h.box = {100, 100, 50, 60};
  h.height_m = height_m;
  h.width_m = width_m;
  h.distance_m = 15.0f;
  return h;
}

NormalStats stats(int id, int normals, float ground, float object, float error, float density = 0.9f) {
  NormalStats s;
  s.roi_id = id;
  s.num_normals = normals;
  s.num_samples = static_cast<int>(std::ceil(normals / density));
  s.density = density;
  s.ground_fraction = ground;
  s.object_fraction = object;
  s.error_fraction = error;
  s.tilt_from_ground_deg = 90.0f;  // an upright representative normal unless a test says otherwise
  return s;
}

TEST(validatorClassify, ObjectIsKept) {
  const NormalStats s = stats(1, 200, 0.05f, 0.8f, 0.0f);
  const Verdict v = classify(hyp(1), &s, Params{});
  EXPECT_EQ(v.label, "object");
  EXPECT_TRUE(v.kept);
  EXPECT_FLOAT_EQ(v.score, 0.8f);
  EXPECT_TRUE(v.reason.empty());
}

TEST(validatorClassify, GroundIsRejectedWithPercentage) {
  const NormalStats s = stats(2, 300, 0.78f, 0.1f, 0.0f);
  const Verdict v = classify(hyp(2), &s, Params{});
  EXPECT_EQ(v.label, "ground");
  EXPECT_FALSE(v.kept);
  EXPECT_FLOAT_EQ(v.score, 0.78f);
  EXPECT_EQ(v.reason, "ground normals 78%");
}

TEST(validatorClassify, DenseErrorIsRejected) {
  const NormalStats s = stats(3, 400, 0.0f, 0.05f, 0.65f, 0.95f);
  const Verdict v = classify(hyp(3), &s, Params{});
  EXPECT_EQ(v.label, "error");
  EXPECT_FALSE(v.kept);
  EXPECT_FLOAT_EQ(v.score, 0.65f);
  EXPECT_EQ(v.reason, "error-like normals 65%, no horizontal component (density 95%)");
}

TEST(validatorClassify, SparseErrorLikeNormalsAreNotEnoughForError) {
  // Error-like but sparse: not the dense blob the error class describes.
  const NormalStats s = stats(4, 40, 0.0f, 0.1f, 0.8f, 0.2f);
  const Verdict v = classify(hyp(4), &s, Params{});
  EXPECT_EQ(v.label, "unvalidated");
  EXPECT_TRUE(v.kept);
  EXPECT_EQ(v.reason, "unvalidated: mixed normals: object 10% (< 30%), ground 0%, error-like 80%");
}

TEST(validatorClassify, SurfaceTiltedLikeTheRoadIsGround) {
  // A raised lawn: few object normals, representative normal 6 deg from the road's.
  NormalStats s = stats(4, 120, 0.45f, 0.16f, 0.0f);
  s.tilt_from_ground_deg = 6.0f;
  const Verdict v = classify(hyp(4, 0.6f), &s, Params{});
  EXPECT_EQ(v.label, "ground");
  EXPECT_FALSE(v.kept);
  EXPECT_NEAR(v.score, 1.0f - 6.0f / 90.0f, 1e-6);
  EXPECT_EQ(v.reason, "surface tilted 6 deg from the road, object normals 16% (< 30%)");
}

TEST(validatorClassify, TiltedSurfaceRuleNeedsEvidenceAndFewObjectNormals) {
  NormalStats few = stats(5, 12, 0.3f, 0.1f, 0.0f);  // < min_surface_normals (20): a far car
  few.tilt_from_ground_deg = 4.0f;
  EXPECT_EQ(classify(hyp(5), &few, Params{}).label, "unvalidated");
  NormalStats objecty = stats(6, 200, 0.2f, 0.35f, 0.0f);  // enough object normals: kept
  objecty.tilt_from_ground_deg = 10.0f;
  EXPECT_EQ(classify(hyp(6), &objecty, Params{}).label, "object");
  NormalStats steep = stats(7, 200, 0.2f, 0.2f, 0.0f);  // tilted 40 deg: not a road-like surface
  steep.tilt_from_ground_deg = 40.0f;
  EXPECT_EQ(classify(hyp(7), &steep, Params{}).label, "unvalidated");
  Params off;
  off.max_surface_tilt_deg = 0.0f;  // rule disabled
  NormalStats lawn = stats(8, 200, 0.4f, 0.1f, 0.0f);
  lawn.tilt_from_ground_deg = 5.0f;
  EXPECT_EQ(classify(hyp(8), &lawn, off).label, "unvalidated");
  EXPECT_EQ(classify(hyp(8), &lawn, Params{}).label, "ground");
}

TEST(validatorClassify, NoStatsIsUnvalidatedAndKeptByDefault) {
  const Verdict v = classify(hyp(5), nullptr, Params{});
  EXPECT_EQ(v.label, "unvalidated");
  EXPECT_TRUE(v.kept);
  EXPECT_EQ(v.score, 0.0f);
  EXPECT_EQ(v.reason, "unvalidated: no normals");
  Params drop;
  drop.keep_unvalidated = false;
  const Verdict d = classify(hyp(5), nullptr, drop);
  EXPECT_EQ(d.label, "unvalidated");
  EXPECT_FALSE(d.kept);
  EXPECT_EQ(d.reason, "unvalidated: no normals");
}

TEST(validatorClassify, TooFewOrInvalidNormalsAreUnvalidated) {
  NormalStats few = stats(6, 3, 0.0f, 1.0f, 0.0f);
  EXPECT_EQ(classify(hyp(6), &few, Params{}).reason, "unvalidated: only 3 normals (< 5)");
  NormalStats none = stats(6, 0, 0.0f, 0.0f, 0.0f);
  none.num_samples = 100;
  none.density = 0;
  EXPECT_EQ(classify(hyp(6), &none, Params{}).reason, "unvalidated: no normals");
  EXPECT_TRUE(classify(hyp(6), &none, Params{}).kept);
  // Measured but empty, and low (a kerb): removed like a box with too few normals.
  const Verdict low = classify(hyp(6, 0.4f), &none, Params{});
  EXPECT_FALSE(low.kept);
  EXPECT_EQ(low.reason, "unvalidated: no normals, lower than 0.80 m");
  EXPECT_TRUE(classify(hyp(6, 0.4f), nullptr, Params{}).kept) << "no statistics at all (bad input) stays kept";
  NormalStats nan = stats(6, 100, 0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f);
  const Verdict v = classify(hyp(6), &nan, Params{});
  EXPECT_EQ(v.label, "unvalidated");
  EXPECT_EQ(v.reason, "unvalidated: invalid normal statistics");
}

TEST(validatorClassify, ImplausibleSizeIsError) {
  const NormalStats s = stats(7, 200, 0.0f, 0.9f, 0.0f);
  Verdict v = classify(hyp(7, 0.08f), &s, Params{});
  EXPECT_EQ(v.label, "error");
  EXPECT_FALSE(v.kept);
  EXPECT_EQ(v.reason, "height 0.08 m below 0.20 m");
  v = classify(hyp(7, 6.0f), &s, Params{});
  EXPECT_EQ(v.reason, "height 6.00 m above 4.50 m");
  v = classify(hyp(7, 1.5f, 20.0f), &s, Params{});
  EXPECT_EQ(v.reason, "width 20.00 m above 12.00 m");
  // Unknown size (0) is not judged.
  EXPECT_EQ(classify(hyp(7, 0.0f, 0.0f), &s, Params{}).label, "object");
}

TEST(validatorClassify, TallNarrowBoxIsAPoleNotAnError) {
  const NormalStats s = stats(9, 60, 0.0f, 0.7f, 0.0f);
  EXPECT_EQ(classify(hyp(9, 8.5f, 0.9f), &s, Params{}).label, "object");  // a tram-wire pole
  EXPECT_EQ(classify(hyp(9, 8.5f, 3.0f), &s, Params{}).reason, "height 8.50 m above 4.50 m");
  Params no_poles;
  no_poles.pole_max_width_m = 0.0f;
  EXPECT_EQ(classify(hyp(9, 8.5f, 0.9f), &s, no_poles).label, "error");
}

TEST(validatorClassify, TiltRuleOnlyNearerThanItsDistance) {
  NormalStats front = stats(10, 60, 0.25f, 0.15f, 0.0f);  // a far car front, normals 12 deg from the road
  front.tilt_from_ground_deg = 12.0f;
  Hypothesis far = hyp(10);
  far.distance_m = 40.0f;
  EXPECT_EQ(classify(far, &front, Params{}).label, "unvalidated");
  far.distance_m = 20.0f;
  EXPECT_EQ(classify(far, &front, Params{}).label, "ground");
}

TEST(validatorClassify, LowUndecidedBoxesAreRemovedWithTheReason) {
  const NormalStats mixed = stats(11, 40, 0.3f, 0.1f, 0.0f);
  const Verdict low = classify(hyp(11, 0.4f), &mixed, Params{});
  EXPECT_EQ(low.label, "unvalidated");
  EXPECT_FALSE(low.kept);
  EXPECT_NE(low.reason.find("mixed normals"), std::string::npos);
  EXPECT_NE(low.reason.find("lower than 0.80 m"), std::string::npos) << low.reason;
  EXPECT_TRUE(classify(hyp(11, 1.2f), &mixed, Params{}).kept);  // tall enough: kept unvalidated
  const NormalStats few = stats(11, 3, 0.0f, 1.0f, 0.0f);
  EXPECT_FALSE(classify(hyp(11, 0.4f), &few, Params{}).kept);
  // Missing statistics stay an explicit, kept "unvalidated" whatever the size.
  const Verdict missing = classify(hyp(11, 0.4f), nullptr, Params{});
  EXPECT_TRUE(missing.kept);
  EXPECT_EQ(missing.reason, "unvalidated: no normals");
}

TEST(validatorClassify, GroundNeedsEnoughNormals) {
  const NormalStats thin = stats(12, 9, 1.0f, 0.0f, 0.0f);  // a far post: 9 normals, all ground-like
  EXPECT_EQ(classify(hyp(12), &thin, Params{}).label, "unvalidated");
  const NormalStats enough = stats(12, 10, 1.0f, 0.0f, 0.0f);
  EXPECT_EQ(classify(hyp(12), &enough, Params{}).label, "ground");
}

TEST(validatorValidate, MatchesByIdAndHandlesUnknownAndMissing) {
  const std::vector<Hypothesis> hyps = {hyp(10), hyp(11), hyp(12)};
  const std::vector<NormalStats> st = {stats(12, 200, 0.9f, 0.0f, 0.0f),   // out of order
                                       stats(99, 200, 0.0f, 1.0f, 0.0f),   // unknown id
                                       stats(10, 200, 0.0f, 0.9f, 0.0f)};
  const std::vector<Verdict> v = validate(hyps, st, Params{});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].roi_id, 10);
  EXPECT_EQ(v[0].label, "object");
  EXPECT_EQ(v[1].roi_id, 11);
  EXPECT_EQ(v[1].label, "unvalidated");  // missing
  EXPECT_EQ(v[1].reason, "unvalidated: no normals");
  EXPECT_EQ(v[2].roi_id, 12);
  EXPECT_EQ(v[2].label, "ground");
  EXPECT_TRUE(validate({}, st, Params{}).empty());
}

TEST(validatorParams, ReadsSectionAndRejectsBadKeys) {
  // Every key given: common/config.cpp currently throws on a key that is
  // missing from a section (ConfigSection::scalar returns YAML::Node(), which
  // is a defined Null node) - reported to the lead, not this library's file.
  YAML::Node n = YAML::Load(
      "min_object_fraction: 0.4\nmax_ground_fraction: 0.6\nmax_error_fraction: 0.6\n"
      "min_normals: 12\nmin_error_density: 0.5\nkeep_unvalidated: false\nmin_height_m: 0.2\n"
      "max_height_m: 3.5\nmax_width_m: 12\nmax_surface_tilt_deg: 20\nmin_surface_normals: 30\n");
  ConfigSection s(n, "validator");
  const Params p = readParams(s);
  s.finish();
  EXPECT_FLOAT_EQ(p.min_object_fraction, 0.4f);
  EXPECT_FALSE(p.keep_unvalidated);
  EXPECT_EQ(p.min_normals, 12);
  EXPECT_FLOAT_EQ(p.max_height_m, 3.5f);
  EXPECT_FLOAT_EQ(p.max_surface_tilt_deg, 20.0f);
  EXPECT_EQ(p.min_surface_normals, 30);

  YAML::Node bad = YAML::Clone(n);
  bad["max_error_fraction"] = 1.5;
  ConfigSection bad_range(bad, "validator");
  EXPECT_THROW(readParams(bad_range), ConfigError);
  YAML::Node typo = YAML::Clone(n);
  typo["min_objct_fraction"] = 0.2;
  ConfigSection unknown(typo, "validator");
  readParams(unknown);
  EXPECT_THROW(unknown.finish(), ConfigError);
}

}  // namespace
}  // namespace nerv::validator

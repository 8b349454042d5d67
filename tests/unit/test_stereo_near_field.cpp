// The near field beyond the search range (near_field.hpp): the fusion rule on
// hand-made maps, and the matcher on a textured plane with a box nearer than
// num_disparities reaches.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "dataset.hpp"
#include "detection_eval.hpp"
#include "kitti_labels.hpp"
#include "near_field.hpp"
#include "scene_yaml.hpp"
#include "sequence.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"

using namespace nerv;
using namespace nerv::stereo;
namespace fs = std::filesystem;

namespace {

cv::Mat texture(int rows, int cols, uint64_t seed) {
  cv::Mat t(rows, cols, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(t, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(t, t, cv::Size(0, 0), 0.8);
  return t;
}

// A textured background plane at `far_px` and a textured box (columns [x0, x1),
// rows [y0, y1) of the left view) at `near_px`, both fronto-parallel.
struct BoxScene {
  cv::Mat left, right;
  cv::Rect box;
};
BoxScene boxScene(int near_px, int far_px = 20) {
  const int W = 640, H = 240, pad = 300;
  // The right view reads the background up to x + far_px + pad: wide enough for that.
  const cv::Mat back = texture(H, W + pad + far_px, 1), front = texture(H, W + pad + far_px, 2);
  BoxScene s;
  s.box = cv::Rect(220, 60, 240, 140);
  s.left.create(H, W, CV_8UC1);
  s.right.create(H, W, CV_8UC1);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      s.left.at<uint8_t>(y, x) = (s.box.contains({x, y}) ? front : back).at<uint8_t>(y, x + pad);
      // right view: the background moved by far_px, the box drawn over it moved by near_px
      const bool on_box = s.box.contains({x + near_px, y});
      s.right.at<uint8_t>(y, x) = on_box ? front.at<uint8_t>(y, x + near_px + pad)
                                         : back.at<uint8_t>(y, x + far_px + pad);
    }
  return s;
}

// Share of the box's inner pixels (a 16 px margin: the quarter-resolution census and
// fattening) within tol of `want`, and the share of valid ones.
std::pair<double, double> boxShares(const cv::Mat& d, cv::Rect box, float want, float tol) {
  const cv::Rect inner(box.x + 16, box.y + 16, box.width - 32, box.height - 32);
  int near = 0, valid = 0;
  for (int y = inner.y; y < inner.y + inner.height; ++y)
    for (int x = inner.x; x < inner.x + inner.width; ++x) {
      const float v = d.at<float>(y, x);
      valid += v > 0;
      near += std::abs(v - want) <= tol;
    }
  return {double(near) / inner.area(), double(valid) / inner.area()};
}

}  // namespace

TEST(stereoNearField, FusionReplacesOnlyBeyondTheReach) {
  // Full resolution 8 x 8, near field 2 x 2 (scale 4), reach 128 px.
  cv::Mat full(8, 8, CV_32F, cv::Scalar(50)), conf(8, 8, CV_32F, cv::Scalar(0.5));
  cv::Mat near(2, 2, CV_32F), near_conf(2, 2, CV_32F, cv::Scalar(0.9));
  near.at<float>(0, 0) = 160.0f / 4;  // beyond the reach, over nothing at full resolution
  near.at<float>(0, 1) = 200.0f / 4;  // beyond the reach, over a (necessarily wrong) 20 px
  near.at<float>(1, 0) = 130.0f / 4;  // within the margin above the reach
  near.at<float>(1, 1) = 0;           // invalid
  full(cv::Rect(0, 0, 4, 4)).setTo(0);
  full(cv::Rect(4, 0, 4, 4)).setTo(20);
  NearFieldParams p;
  EXPECT_EQ(fuseNearField(full, conf, near, near_conf, p), 32);
  EXPECT_FLOAT_EQ(full.at<float>(1, 1), 160.0f);
  EXPECT_FLOAT_EQ(conf.at<float>(1, 1), 0.9f);
  EXPECT_FLOAT_EQ(full.at<float>(3, 7), 200.0f);
  EXPECT_FLOAT_EQ(full.at<float>(5, 1), 50.0f);  // 130 < 128 + 4: the main search may hold it
  EXPECT_FLOAT_EQ(conf.at<float>(5, 1), 0.5f);
  EXPECT_FLOAT_EQ(full.at<float>(6, 6), 50.0f);  // near field invalid
}

TEST(stereoNearField, ABoxNearerThanTheSearchRangeIsMeasured) {
  for (const int near_px : {160, 200}) {
    const BoxScene s = boxScene(near_px);
    Params on, off;
    off.near_field = false;
    cv::Mat d_on, d_off;
    const auto m_on = StereoMatcher::create(on);
    m_on->compute(s.left, s.right, d_on);
    StereoMatcher::create(off)->compute(s.left, s.right, d_off);
    EXPECT_EQ(m_on->nearFieldPixels(), cv::countNonZero(d_on != d_off)) << near_px;  // what the service counts
    EXPECT_GT(m_on->nearFieldPixels(), s.box.area() / 2) << near_px;
    const auto [within_on, valid_on] = boxShares(d_on, s.box, static_cast<float>(near_px), 4.0f);
    const auto [within_off, valid_off] = boxShares(d_off, s.box, static_cast<float>(near_px), 4.0f);
    // 128 disparities end at 3.0 m on KITTI: without the near field no box pixel is right
    // (most read the background's 20 px, carried in by the paths) ...
    EXPECT_EQ(within_off, 0.0) << near_px << " (valid " << valid_off << ")";
    // ... and with it almost all of it is, within one quarter-resolution step.
    EXPECT_GT(within_on, 0.85) << near_px << " (valid " << valid_on << ")";
    // The background keeps the full-resolution values (20 px, exact here).
    const cv::Rect back(20, 20, 150, 200);
    EXPECT_EQ(cv::countNonZero(d_on(back) != d_off(back)), 0) << near_px;
  }
}

TEST(stereoNearField, InRangeScenesAreUnchanged) {
  const BoxScene s = boxScene(90, 30);  // both within 128
  Params on, off;
  off.near_field = false;
  cv::Mat d_on, c_on, d_off, c_off;
  const auto m_on = StereoMatcher::create(on);
  m_on->compute(s.left, s.right, d_on, c_on);
  StereoMatcher::create(off)->compute(s.left, s.right, d_off, c_off);
  EXPECT_EQ(m_on->nearFieldPixels(), 0);
  EXPECT_EQ(cv::countNonZero(d_on != d_off), 0);
  EXPECT_EQ(cv::countNonZero(c_on != c_off), 0);
  EXPECT_GT(boxShares(d_on, s.box, 90.0f, 1.0f).first, 0.9);
}

TEST(stereoNearField, ConfigKeyAndCacheKey) {
  Params p;
  EXPECT_TRUE(p.near_field);
  Params q = p;
  q.near_field = false;
  EXPECT_NE(describeParams(p), describeParams(q));  // disparity caches tell them apart
}

TEST(stereoNearField, TheCarAheadInStopAndGoIsDetectedAtItsDepth) {
  // config/scenes/near_car.yaml: the car ahead's rear 2.3 m from the camera (about 170 px).
  const fs::path dir = fs::temp_directory_path() / ("nerv_near_car_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  synth::RenderOptions ro;
  ro.supersample = 1;
  synth::writeSequence(synth::loadScene(std::string(NERV_SOURCE_DIR) + "/config/scenes/near_car.yaml"), 2,
                       dir.string(), ro);
  const Dataset ds = openDataset(dir.string());
  ASSERT_EQ(ds.frames.size(), 2u);
  Params off;
  off.near_field = false;
  auto with = StereoMatcher::create(Params{}), without = StereoMatcher::create(off);
  for (const DatasetFrame& f : ds.frames) {
    // the car ahead: the label nearest the camera, straight ahead
    KittiLabel car;
    for (const KittiLabel& l : readKittiLabels(f.label_path))
      if (l.type == "Car" && std::abs(l.x) < 0.5f && (car.type.empty() || l.z < car.z)) car = l;
    ASSERT_EQ(car.type, "Car") << f.name;
    const cv::Mat truth = cv::imread((dir / "disp_occ_0" / (f.name + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(truth.empty());
    const cv::Rect lb(int(car.x1), int(car.y1), int(car.x2 - car.x1) + 1, int(car.y2 - car.y1) + 1);
    const cv::Mat roi = truth(lb & cv::Rect(0, 0, truth.cols, truth.rows));
    std::vector<uint16_t> t(roi.begin<uint16_t>(), roi.end<uint16_t>());
    std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
    const float true_d = t[t.size() / 2] / 256.0f;  // the rendered disparity (1/256 px)
    ASSERT_GT(true_d, 140.0f) << "the car must be nearer than 128 disparities reach";
    const float true_z = static_cast<float>(f.camera.fx * f.camera.baseline_m / true_d);
    const cv::Mat left = cv::imread(f.left_path, cv::IMREAD_GRAYSCALE), right = cv::imread(f.right_path, cv::IMREAD_GRAYSCALE);
    for (const bool near_field : {true, false}) {
      cv::Mat d;
      (near_field ? with : without)->compute(left, right, d);
      stixel::GroundPrior prior;
      const stixel::StixelResult st = stixel::estimateStixels(d, f.camera, stixel::Params{}, prior);
      const EvalBox label = labelBox(car);
      const Hypothesis* hit = nullptr;
      for (const Hypothesis& h : st.hypotheses)
        if (iou(detectionBox(h.box.x, h.box.y, h.box.w, h.box.h), label) > 0.5f) hit = &h;
      if (near_field) {
        ASSERT_NE(hit, nullptr) << f.name << ": the car " << true_z << " m ahead is not found";
        EXPECT_NEAR(hit->nearest_z_m, true_z, 0.15f) << f.name;
        std::printf("near_car %s: the car %.2f m ahead (%.0f px) found at %.2f m\n", f.name.c_str(), true_z, true_d,
                    hit->nearest_z_m);
      } else {
        EXPECT_EQ(hit, nullptr) << f.name << ": without the near field the car should be lost (the reason it exists)";
      }
      // Free or unseen (observed_free_space.hpp): lost, the car leaves its strips without
      // disparity, and they must read as unknown rather than free; found, it bounds them.
      const int w = st.observed.column_width_px;
      int strips = 0, unobserved = 0;
      for (int k = (static_cast<int>(car.x1) + w - 1) / w; (k + 1) * w <= static_cast<int>(car.x2); ++k, ++strips)
        unobserved += st.observed.observed[k] < st.observed.min_observed ? 1 : 0;
      ASSERT_GT(strips, 20) << f.name;
      if (near_field) EXPECT_LT(unobserved, strips / 5) << f.name << ": the found car's strips read as unseen";
      else EXPECT_GT(unobserved, strips * 4 / 5) << f.name << ": the lost car's strips read as free";
      std::printf("near_car %s, near field %s: %d of the car's %d strips unobserved\n", f.name.c_str(),
                  near_field ? "on" : "off", unobserved, strips);
    }
  }
  fs::remove_all(dir);
}

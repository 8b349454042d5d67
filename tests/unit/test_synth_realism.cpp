// Realism of the rendered images for a real stereo matcher: OpenCV SGBM on the
// `urban` preset must reach a low D1 error outside traps, and the traps of
// `wet_road` must make it fail inside them.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdio>

#include "scene_yaml.hpp"
#include "sequence.hpp"

namespace {

using namespace nerv::synth;

struct D1 {
  long pixels = 0, errors = 0, invalid = 0;
  double rate() const { return pixels ? double(errors) / pixels : 0; }
  double density() const { return pixels + invalid ? double(pixels) / (pixels + invalid) : 0; }
};

// SGBM as in the brief: 3-way, block 5, P1 = 8*25, P2 = 32*25, 128 levels, gray.
cv::Mat sgbm(const cv::Mat& left, const cv::Mat& right) {
  cv::Mat gl, gr, raw, disp;
  cv::cvtColor(left, gl, cv::COLOR_BGR2GRAY);
  cv::cvtColor(right, gr, cv::COLOR_BGR2GRAY);
  auto m = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25);
  m->setMode(cv::StereoSGBM::MODE_SGBM_3WAY);
  m->compute(gl, gr, raw);
  raw.convertTo(disp, CV_32F, 1.0 / cv::StereoMatcher::DISP_SCALE);
  return disp;
}

// D1 (KITTI): |d - gt| > 3 px and > 5 % of gt, over pixels with ground truth
// where the matcher gave a value; `want_trap` selects inside/outside traps.
// Columns left of 128 px are skipped: SGBM cannot search the full range there.
void accumulate(const cv::Mat& disp, const SynthFrame& f, bool want_trap, D1& acc) {
  for (int v = 0; v < disp.rows; ++v)
    for (int u = 128; u < disp.cols; ++u) {
      const float gt = f.images.disparity.at<float>(v, u);
      if (gt <= 0 || (f.images.trap_mask.at<uchar>(v, u) != 0) != want_trap) continue;
      const float d = disp.at<float>(v, u);
      if (d < 0) {
        ++acc.invalid;
        continue;
      }
      ++acc.pixels;
      const float e = std::abs(d - gt);
      acc.errors += e > 3.0f && e > 0.05f * gt;
    }
}

SceneSpec preset(const char* name) {
  return loadScene(resolveScenePath(name, NERV_SOURCE_DIR "/config/scenes"));
}

TEST(synthRealism, SgbmD1OnUrbanIsLowOutsideTraps) {
  SceneSequence seq(preset("urban"));
  D1 outside;
  for (int frame : {0, 5, 10}) {
    const SynthFrame f = seq.render(frame);
    accumulate(sgbm(f.images.left, f.images.right), f, false, outside);
  }
  std::printf("urban: D1 outside traps %.2f %% over %ld px (density %.1f %%)\n", 100 * outside.rate(),
              outside.pixels, 100 * outside.density());
  ASSERT_GT(outside.pixels, 100000);
  EXPECT_LT(outside.rate(), 0.10);
  EXPECT_GT(outside.density(), 0.8);
}

TEST(synthRealism, WetRoadTrapsMakeSgbmFail) {
  SceneSequence seq(preset("wet_road"));
  D1 inside, outside;
  for (int frame : {0, 5, 10}) {
    const SynthFrame f = seq.render(frame);
    const cv::Mat d = sgbm(f.images.left, f.images.right);
    accumulate(d, f, true, inside);
    accumulate(d, f, false, outside);
  }
  std::printf("wet_road: D1 inside traps %.2f %% over %ld px, outside %.2f %% over %ld px\n",
              100 * inside.rate(), inside.pixels, 100 * outside.rate(), outside.pixels);
  ASSERT_GT(inside.pixels, 5000);
  EXPECT_LT(outside.rate(), 0.10);
  EXPECT_GT(inside.rate(), 0.30);
  EXPECT_GT(inside.rate(), 3 * outside.rate());
}

}  // namespace

namespace {

TEST(synthRealism, TexturelessAndRepetitiveTrapsRaiseSgbmError) {
  SceneSequence seq(preset("textureless"));
  D1 inside, outside;
  for (int frame : {0, 8}) {
    const SynthFrame f = seq.render(frame);
    const cv::Mat d = sgbm(f.images.left, f.images.right);
    accumulate(d, f, true, inside);
    accumulate(d, f, false, outside);
  }
  std::printf("textureless: D1 inside traps %.2f %% over %ld px (density %.1f %%), outside %.2f %% over %ld px\n",
              100 * inside.rate(), inside.pixels, 100 * inside.density(), 100 * outside.rate(), outside.pixels);
  ASSERT_GT(inside.pixels, 5000);
  EXPECT_LT(outside.rate(), 0.10);
  EXPECT_GT(inside.rate(), 2 * outside.rate());
}

}  // namespace

// Two rendered frames of the urban street as the stereo_matcher's motion checks see them
// (shutter_sync.hpp, disparity_offset.hpp): the earlier left view, and the next pair with its
// disparity; the right view optionally late or moved sideways.
#pragma once

#include <opencv2/imgproc.hpp>

#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "scene_yaml.hpp"
#include "sequence.hpp"
#include "stereo_matcher.hpp"

namespace nerv::stereo::test {

struct Pair {
  cv::Mat previous_left, left, right, disparity;  // frame k-1's left view; frame k as matched
  double fx = 0, cx = 0, cy = 0, baseline_m = 0;
};

inline cv::Mat gray(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

inline synth::SceneSequence& urbanSequence() {
  static synth::SceneSequence seq(
      synth::loadScene(synth::resolveScenePath("urban", std::string(NERV_SOURCE_DIR) + "/config/scenes")));
  return seq;
}

// Frame k of the urban scene (ego 8 m/s, 10 frames a second), its right view taken delay_ms
// after its left and moved shift_px to the left (every disparity shift_px larger, as a right
// camera turned about its vertical axis gives), then matched by nerv_sgm; no previous_left.
inline const Pair& renderedFrame(int k, double delay_ms, double shift_px = 0) {
  static std::map<std::tuple<int, double, double>, Pair> cache;
  auto it = cache.find({k, delay_ms, shift_px});
  if (it != cache.end()) return it->second;
  synth::SceneSequence& seq = urbanSequence();
  synth::RenderOptions options;
  options.right_delay_s = delay_ms / 1000.0;
  const synth::SynthFrame f = seq.render(k, options);
  Pair p;
  p.left = gray(f.images.left);
  p.right = gray(f.images.right);
  if (shift_px != 0) {
    const cv::Mat move = (cv::Mat_<double>(2, 3) << 1, 0, -shift_px, 0, 1, 0);
    cv::warpAffine(p.right, p.right, move, p.right.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  }
  static const std::unique_ptr<StereoMatcher> matcher = StereoMatcher::create(Params{});
  cv::Mat confidence;
  matcher->compute(p.left, p.right, p.disparity, confidence);
  p.fx = seq.camera().fx, p.cx = seq.camera().cx, p.cy = seq.camera().cy, p.baseline_m = seq.camera().baseline_m;
  return cache.emplace(std::make_tuple(k, delay_ms, shift_px), p).first->second;
}

// Frames k - 1 and k: frame k as renderedFrame gives it, with frame k - 1's left view.
inline const Pair& renderedPair(int k, double delay_ms, double shift_px = 0) {
  static std::map<std::tuple<int, double, double>, Pair> cache;
  auto it = cache.find({k, delay_ms, shift_px});
  if (it != cache.end()) return it->second;
  Pair p = renderedFrame(k, delay_ms, shift_px);
  p.previous_left = gray(urbanSequence().render(k - 1, synth::RenderOptions{}).images.left);
  return cache.emplace(std::make_tuple(k, delay_ms, shift_px), p).first->second;
}

}  // namespace nerv::stereo::test

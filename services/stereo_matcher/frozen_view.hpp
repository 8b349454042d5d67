// Has one camera stopped? A stuck camera or driver can go on delivering its last image while
// the other camera runs: every pair then compares images taken at different times, and on a
// moving vehicle the disparity is wrong everywhere without any other sign. Real sensors
// never give two bit-identical frames in a row (noise), so a view whose image repeats
// exactly while the other view's changes has stopped. Both views repeating is a still frame
// sent again (a replay, a test pattern): not this fault, and not counted.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <string>

namespace nerv::stereo {

// A 64-bit digest of an image's pixels (FNV-1a over its rows, 8 bytes at a time).
uint64_t imageDigest(const cv::Mat& image);

class FrozenViewCheck {
 public:
  explicit FrozenViewCheck(int min_frames = 3) : min_frames_(min_frames < 1 ? 1 : min_frames) {}
  // The next pair. Returns "" or, from the min_frames-th pair in a row in which one view
  // repeated while the other changed, "left" or "right": the view that stopped.
  std::string push(const cv::Mat& left, const cv::Mat& right);
  int framesStopped() const { return run_; }  // pairs in a row with the same view stopped

 private:
  int min_frames_;
  bool have_previous_ = false;
  uint64_t left_ = 0, right_ = 0;
  std::string stopped_;  // the view of the current run
  int run_ = 0;
};

}  // namespace nerv::stereo

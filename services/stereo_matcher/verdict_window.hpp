// The last `window` measurements of a rig check, and when a verdict over them is due: after
// every `window` added, so that one frame of glare or blur decides nothing. Shared by the
// row check's and the shutter check's monitors (rectification_check.hpp, shutter_sync.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

#include "percentile.hpp"

namespace nerv::stereo {

template <typename T>
class VerdictWindow {
 public:
  explicit VerdictWindow(int window) : window_(window < 1 ? 1 : window) {}
  // Remembers m (forgetting the oldest beyond the window); true when a verdict is due.
  bool add(const T& m) {
    items_.push_back(m);
    while (static_cast<int>(items_.size()) > window_) items_.pop_front();
    if (++since_verdict_ < window_) return false;
    since_verdict_ = 0;
    return true;
  }
  // Forgets everything: the next verdict is of the `window` that follow.
  void restart() { items_.clear(), since_verdict_ = 0; }
  const std::deque<T>& items() const { return items_; }
  int size() const { return static_cast<int>(items_.size()); }

 private:
  int window_;
  int since_verdict_ = 0;
  std::deque<T> items_;
};

// The median of the last `window` values of one measured quantity, a verdict every `window`
// values, and whether the median lies beyond a limit either way (the shutter delay, the
// disparity offset).
class MedianVerdict {
 public:
  MedianVerdict(int window, float limit) : values_(window), limit_(limit) {}
  // Non-finite values are ignored. True when a verdict is due.
  bool add(float v) { return std::isfinite(v) && values_.add(v); }
  int samples() const { return values_.size(); }
  float median() const {
    return static_cast<float>(percentile(std::vector<double>(values_.items().begin(), values_.items().end()), 0.5));
  }
  float lowest() const { return samples() ? *std::min_element(values_.items().begin(), values_.items().end()) : 0; }
  float highest() const { return samples() ? *std::max_element(values_.items().begin(), values_.items().end()) : 0; }
  bool beyond() const { return samples() > 0 && std::abs(median()) > limit_; }
  // Forgets the values: the next verdict is of the `window` that follow.
  void restart() { values_.restart(); }
  float limit() const { return limit_; }

 private:
  VerdictWindow<float> values_;
  float limit_;
};

}  // namespace nerv::stereo

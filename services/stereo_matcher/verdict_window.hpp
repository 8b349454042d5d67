// The last `window` measurements of a rig check, and when a verdict over them is due: after
// every `window` added, so that one frame of glare or blur decides nothing. Shared by the
// row check's and the shutter check's monitors (rectification_check.hpp, shutter_sync.hpp).
#pragma once

#include <deque>

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

}  // namespace nerv::stereo

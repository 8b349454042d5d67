#include "seq_gap_tracker.hpp"

namespace nerv {

int64_t SeqGapTracker::note(int64_t seq) {
  constexpr int64_t kFar = 1000;
  if (!started_ || seq - newest_ >= kFar || newest_ - seq >= kFar) {
    started_ = true;
    newest_ = seq;
    missing_.clear();
    return 0;
  }
  if (seq <= newest_) {
    missing_.erase(seq);  // a late one, a duplicate or a replayed one: no longer missing
    return 0;
  }
  for (int64_t s = newest_ + 1; s < seq; ++s) missing_.insert(s);
  newest_ = seq;
  int64_t lost = 0;
  while (!missing_.empty() && newest_ - *missing_.begin() >= window_) {
    missing_.erase(missing_.begin());
    ++lost;
  }
  return lost;
}

}  // namespace nerv

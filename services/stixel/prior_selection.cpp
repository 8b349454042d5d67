#include "prior_selection.hpp"

#include <algorithm>

namespace nerv::stixel {

PriorSelection::PriorSelection(int max_age_frames, int64_t max_age_us, int capacity)
    : max_age_frames_(std::max(0, max_age_frames)),
      max_age_us_(std::max<int64_t>(0, max_age_us)),
      capacity_(static_cast<size_t>(std::max(1, capacity))) {
  entries_.reserve(capacity_);
}

void PriorSelection::offer(int64_t seq, int64_t utime, const GroundPrior& prior) {
  if (!prior.valid) return;
  // A pose for a frame already remembered replaces it (a repeated message).
  for (Entry& e : entries_)
    if (e.seq == seq) {
      e.utime = utime;
      e.prior = prior;
      return;
    }
  // Oldest offer first out (not lowest seq): after a restart the old drive's
  // high seqs must leave as the new drive's poses come in.
  if (entries_.size() < capacity_) {
    entries_.push_back({seq, utime, prior});
  } else {
    entries_[next_] = {seq, utime, prior};
  }
  next_ = (next_ + 1) % capacity_;
}

GroundPrior PriorSelection::forFrame(int64_t seq, int64_t utime) const {
  const Entry* best = nullptr;
  for (const Entry& e : entries_) {
    // Unsigned age: seq - e.seq overflows for far-apart seqs (a corrupt header),
    // and the wrapped negative age passed as recent.
    if (e.seq >= seq ||
        static_cast<uint64_t>(seq) - static_cast<uint64_t>(e.seq) > static_cast<uint64_t>(max_age_frames_))
      continue;
    // Captured after the frame, or too long before it: another drive (the same
    // unsigned arithmetic against far-apart times).
    if (max_age_us_ > 0 &&
        (e.utime > utime ||
         static_cast<uint64_t>(utime) - static_cast<uint64_t>(e.utime) > static_cast<uint64_t>(max_age_us_)))
      continue;
    if (!best || e.seq > best->seq) best = &e;
  }
  return best ? best->prior : GroundPrior{};
}

}  // namespace nerv::stixel

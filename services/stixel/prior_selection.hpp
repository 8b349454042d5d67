// Which camera pose from snv_extrinsic a frame may use as its ground prior.
//
// EXTRINSICS for frame k is computed from frame k's STIXELS, so it always
// arrives after them: a frame can only use the pose of an earlier frame. The
// latest message alone is not enough: after the source restarts (a new drive,
// a replay from the start, a shard that fell behind) the latest pose can belong
// to a later seq of another drive, or be minutes old. A prior is therefore
// usable for frame k only if it comes from a frame before k and at most
// max_age_frames before it, captured before frame k and at most max_age_us
// before it. The capture time catches what the seq cannot: a short drive whose
// seqs the next one counts through again (its frame 4 is "before" the new
// frame 5, but minutes older).
#pragma once

#include <cstdint>
#include <vector>

#include "stixel_estimator.hpp"

namespace nerv::stixel {

class PriorSelection {
 public:
  // max_age_frames: the oldest prior a frame may use, in frames (seq) before it.
  // max_age_us: the oldest prior a frame may use, in capture time (header.utime)
  // before it; 0: no limit in time.
  // capacity: how many of the latest offered priors are remembered (sharded
  // pipelines deliver poses out of order).
  explicit PriorSelection(int max_age_frames = 30, int64_t max_age_us = 3'000'000, int capacity = 16);

  // A confident pose estimated for frame `seq`, captured at `utime`.
  void offer(int64_t seq, int64_t utime, const GroundPrior& prior);

  // The prior of the newest remembered frame with seq - max_age <= seq' < seq
  // and utime - max_age_us <= utime' <= utime, or an invalid prior when there is none.
  GroundPrior forFrame(int64_t seq, int64_t utime) const;

 private:
  struct Entry {
    int64_t seq;
    int64_t utime;
    GroundPrior prior;
  };
  int max_age_frames_;
  int64_t max_age_us_;
  size_t capacity_;
  size_t next_ = 0;            // ring position of the next offer
  std::vector<Entry> entries_; // the latest offers, oldest overwritten first
};

}  // namespace nerv::stixel

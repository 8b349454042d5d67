// Messages missing from a channel's seq sequence, counted as lost only once they are
// overdue. Several shards of a stage publish their frames out of order (shard 1's seq
// n + 1 before shard 0's n), so a gap is not yet a loss: a seq still missing after
// `window` newer seqs have arrived is. Without this, every swap counted as one or two
// lost frames (a two-shard run reported 48 "dropped" with none lost).
#pragma once

#include <cstdint>
#include <set>

namespace nerv {

class SeqGapTracker {
 public:
  // window: how far (in seqs) a message may arrive late and still not count as lost.
  explicit SeqGapTracker(int64_t window = 16) : window_(window < 1 ? 1 : window) {}

  // Notes an arrival; returns how many seqs became lost with it. A jump by 1000 or more
  // either way is a restarted source: counting starts again from it, and what was still
  // missing then is not counted. A smaller step back (a message later than the window, a
  // duplicate, a log replayed from its start) changes nothing; counting goes on from the
  // newest seq, so seqs received once are never counted as lost.
  int64_t note(int64_t seq);

  // Seqs missing but not yet overdue.
  int64_t pending() const { return static_cast<int64_t>(missing_.size()); }

 private:
  int64_t window_;
  bool started_ = false;
  int64_t newest_ = 0;
  std::set<int64_t> missing_;
};

}  // namespace nerv

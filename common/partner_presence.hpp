// Whether the partner input of a join is arriving at all. A service that waits
// join_timeout_ms for the partner of every frame delays every frame by that much
// while the partner's stage is down: with snv_extrinsic stopped, the validator
// published each frame's DETECTIONS, all unvalidated, 2 s after its STIXELS.
// Once `absent_after` frames in a row have expired without their partner and none
// has arrived since, the partner is absent: frames go on at once, alone, until it arrives again. A
// partner that arrives for a frame already sent alone is late, not a new frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>

namespace nerv {

class PartnerPresence {
 public:
  // absent_after: frames in a row that expired without the partner.
  explicit PartnerPresence(int absent_after = 1) : absent_after_(absent_after < 1 ? 1 : absent_after) {}

  // A frame expired without its partner.
  void missed() { ++missed_in_a_row_; }
  // A partner message arrived for frame seq; false when that frame was sent alone
  // already (the message is late and must not start a new join).
  bool arrived(int64_t seq);
  bool absent() const { return missed_in_a_row_ >= absent_after_; }
  // The partner's stage announced itself (it started or restarted): wait for its messages
  // again from the next frame on, before the first of them arrives. Otherwise the frames in
  // flight while it starts go on alone and their partners come late. Once only until one of
  // its messages arrives: a stage that restarts again and again without output (a crash loop
  // under a supervisor) would otherwise hold frames back at each restart. Returns whether the
  // frames wait for it again (it was absent and no such start is still unanswered).
  bool expect() {
    if (!absent() || start_unanswered_) return false;
    missed_in_a_row_ = 0;
    start_unanswered_ = true;
    return true;
  }

  // A frame arrived: true when it must go on alone (the partner is absent; noted,
  // so that its partner, should it come after all, is known as late). Otherwise it
  // waits for its partner as usual, and an older note on its seq (a source that
  // restarted its count) is forgotten.
  bool goesAlone(int64_t seq);
  // A frame went on alone after waiting for its partner in vain (an expired join): its
  // partner, should it come after all, is late.
  void wentAlone(int64_t seq);

 private:
  int absent_after_;
  int missed_in_a_row_ = 0;
  bool start_unanswered_ = false;  // expect() made frames wait, and no partner message came since
  std::set<int64_t> sent_alone_;  // the latest ones (kMemory), for late partners
  static constexpr size_t kMemory = 256;
};

}  // namespace nerv

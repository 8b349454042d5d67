// A SeqJoin whose first input goes on alone when its partner does not come: the
// validator's STIXELS without SURFACE_NORMALS (hypotheses unvalidated), snv_extrinsic's
// DISPARITY without STIXELS (the camera pose alone). One mechanism for both services:
// an A whose B expired, or whose B is absent (PartnerPresence: two frames in a row
// without it and none since) goes to `alone` with why; a B for an A already gone on
// alone is `late`, not a new join; a B whose A never came is an `orphan`. While B is
// absent, A does not wait at all, and what was waiting goes on at the next tick.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "partner_presence.hpp"
#include "seq_join.hpp"

namespace nerv {

enum class Alone {
  Waited,      // waited for its partner in vain (join_timeout_ms or join_capacity)
  Flushed,     // was waiting when the partner was found absent
  NotWaiting,  // arrived while the partner was absent: never waited
};

template <class A, class B>
class PartnerJoin {
 public:
  struct Handlers {
    std::function<void(const A&, const B&)> matched;
    std::function<void(const A&, Alone why)> alone;
    std::function<void(const B&)> late;    // for an A already gone on alone
    std::function<void(const B&)> orphan;  // its A never came
  };

  // absent_after: frames in a row without a partner that make it absent (2: a single
  // lost message is not a stage down).
  PartnerJoin(size_t capacity, int64_t max_wait_us, int absent_after, Handlers handlers)
      : presence_(absent_after),
        handlers_(std::move(handlers)),
        join_(capacity, max_wait_us, handlers_.matched,
              [this](const std::optional<A>& a, const std::optional<B>& b) {
                if (!a) return handlers_.orphan(*b);
                const Alone why = presence_.absent() ? Alone::Flushed : Alone::Waited;
                if (why == Alone::Waited) presence_.missed();
                presence_.wentAlone(seqOf(*a));
                handlers_.alone(*a, why);
              }) {}

  PartnerJoin(const PartnerJoin&) = delete;  // the join's callback holds `this`
  PartnerJoin& operator=(const PartnerJoin&) = delete;

  void pushA(int64_t seq, const A& a, int64_t now_us) {
    if (presence_.goesAlone(seq)) return handlers_.alone(a, Alone::NotWaiting);
    join_.pushA(seq, a, now_us);
  }
  void pushB(int64_t seq, const B& b, int64_t now_us) {
    if (!presence_.arrived(seq)) return handlers_.late(b);
    join_.pushB(seq, b, now_us);
  }
  // The partner's stage started: frames wait for it again (PartnerPresence::expect).
  bool expectPartner() { return presence_.expect(); }
  // Expires what waited too long; once the partner is absent, everything waiting.
  void tick(int64_t now_us) {
    join_.expire(now_us);
    if (presence_.absent()) join_.expireAll();
  }

 private:
  static int64_t seqOf(const A& a) { return a.header.seq; }
  PartnerPresence presence_;
  Handlers handlers_;
  SeqJoin<A, B> join_;
};

}  // namespace nerv

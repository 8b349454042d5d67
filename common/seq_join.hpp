// Joins two message streams by header.seq in a small bounded buffer. When the
// buffer is full, or an entry waits longer than max_wait_us, the oldest entry
// is handed to on_expired with whatever half it has, so the caller can count
// it or still act on it; nothing disappears silently.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>

namespace nerv {

template <class A, class B>
class SeqJoin {
 public:
  using Matched = std::function<void(const A&, const B&)>;
  using Expired = std::function<void(const std::optional<A>&, const std::optional<B>&)>;

  SeqJoin(size_t capacity, int64_t max_wait_us, Matched on_match, Expired on_expired)
      : capacity_(capacity), max_wait_us_(max_wait_us), on_match_(std::move(on_match)),
        on_expired_(std::move(on_expired)) {}

  void pushA(int64_t seq, const A& a, int64_t now_us) { push(seq, now_us, [&](Entry& e) { e.a = a; }); }
  void pushB(int64_t seq, const B& b, int64_t now_us) { push(seq, now_us, [&](Entry& e) { e.b = b; }); }

  // Expires entries older than max_wait_us.
  void expire(int64_t now_us) {
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (now_us - it->second.arrived_us > max_wait_us_) {
        Entry e = std::move(it->second);
        it = pending_.erase(it);
        on_expired_(e.a, e.b);
      } else {
        ++it;
      }
    }
  }
  // Expires every pending entry now, oldest first (its partner is known not to come).
  void expireAll() {
    while (!pending_.empty()) {
      Entry e = std::move(pending_.begin()->second);
      pending_.erase(pending_.begin());
      on_expired_(e.a, e.b);
    }
  }
  size_t pending() const { return pending_.size(); }

 private:
  struct Entry {
    std::optional<A> a;
    std::optional<B> b;
    int64_t arrived_us = 0;
  };

  template <class Fill>
  void push(int64_t seq, int64_t now_us, Fill fill) {
    auto [it, fresh] = pending_.try_emplace(seq);
    if (fresh) it->second.arrived_us = now_us;
    fill(it->second);
    if (it->second.a && it->second.b) {
      Entry e = std::move(it->second);
      pending_.erase(it);
      on_match_(*e.a, *e.b);
      return;
    }
    while (pending_.size() > capacity_) {
      auto oldest = pending_.begin();
      Entry e = std::move(oldest->second);
      pending_.erase(oldest);
      on_expired_(e.a, e.b);
    }
  }

  size_t capacity_;
  int64_t max_wait_us_;
  Matched on_match_;
  Expired on_expired_;
  std::map<int64_t, Entry> pending_;
};

}  // namespace nerv

// The body of every harness: a broken promise is a finding (abort, libFuzzer
// saves the input); a rejection or a clean acceptance is not.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "receive_paths.hpp"

namespace nerv::fuzz {

inline int harness(const Outcome& o) {
  if (!o.bug.empty()) {
    std::fprintf(stderr, "nerv fuzz finding: %s\n", o.bug.c_str());
    std::abort();
  }
  if (!o.accepted && o.counter.empty()) {
    std::fprintf(stderr, "nerv fuzz finding: rejected without a counter\n");
    std::abort();
  }
  return 0;
}

}  // namespace nerv::fuzz

// Shared by the multiprocess tests' helper programs: the private bus given on
// the command line, and bounded waits that keep LCM's handlers running.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <memory>

namespace nerv::test {

// The bus of argv[1] (LCM's default when absent); nullptr, said on stderr, when LCM cannot start.
inline std::unique_ptr<lcm::LCM> openBus(int argc, char** argv) {
  auto lcm = std::make_unique<lcm::LCM>(argc > 1 ? argv[1] : "");
  if (lcm->good()) return lcm;
  std::fprintf(stderr, "inject: LCM cannot start\n");
  return nullptr;
}

// Handles messages until done() holds or `limit` has passed; returns done().
template <class Done>
bool handleUntil(lcm::LCM& lcm, std::chrono::milliseconds limit, Done done, int step_ms = 50) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (!done() && std::chrono::steady_clock::now() < until) lcm.handleTimeout(step_ms);
  return done();
}

// Handles messages for `time` (the services keep short queues: a message gets
// time to be handled before the next one).
inline void handleFor(lcm::LCM& lcm, std::chrono::milliseconds time) {
  handleUntil(lcm, time, [] { return false; }, 20);
}

}  // namespace nerv::test

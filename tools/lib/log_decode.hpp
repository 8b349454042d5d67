// Decoding a logged event as a given nerv type, recognised by its LCM
// fingerprint so that channel names (and prefixes) do not matter.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <exception>

namespace nerv {

template <class T>
bool decodeEvent(const lcm::LogEvent& e, T& msg) {
  if (e.datalen < 8) return false;
  const auto* b = static_cast<const uint8_t*>(e.data);
  uint64_t h = 0;
  for (int i = 0; i < 8; ++i) h = (h << 8) | b[i];
  if (static_cast<int64_t>(h) != T::getHash()) return false;
  try {
    return msg.decode(e.data, 0, e.datalen) >= 0;
  } catch (const std::exception&) {  // a corrupt array length makes the decoder throw
    return false;
  }
}

}  // namespace nerv

// Decoding a logged event as a given nerv type, recognised by its LCM
// fingerprint so that channel names (and prefixes) do not matter.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <exception>

#include "message_fingerprint.hpp"

namespace nerv {

template <class T>
bool decodeEvent(const lcm::LogEvent& e, T& msg) {
  if (e.datalen < 8 || messageFingerprint(e.data, e.datalen) != T::getHash()) return false;
  try {
    return msg.decode(e.data, 0, e.datalen) >= 0;
  } catch (const std::exception&) {  // a corrupt array length makes the decoder throw
    return false;
  }
}

}  // namespace nerv

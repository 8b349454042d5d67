// Writing a hand-made LCM log in a unit test: messages of one type on one channel, in order.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace nerv::test {

// False when the log cannot be written. Each message's event number is its index, its
// timestamp the index + 1 [us].
template <typename T>
bool writeLcmLog(const std::string& path, const std::string& channel, const std::vector<T>& messages) {
  lcm::LogFile log(path, "w");
  if (!log.good()) return false;
  for (size_t i = 0; i < messages.size(); ++i) {
    std::vector<uint8_t> buf(static_cast<size_t>(messages[i].getEncodedSize()));
    messages[i].encode(buf.data(), 0, static_cast<int>(buf.size()));
    lcm::LogEvent e{};
    e.eventnum = static_cast<int64_t>(i);
    e.timestamp = static_cast<int64_t>(i) + 1;
    e.channel = channel;
    e.datalen = static_cast<int32_t>(buf.size());
    e.data = buf.data();
    log.writeEvent(&e);
  }
  return true;
}

}  // namespace nerv::test

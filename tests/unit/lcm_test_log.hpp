// Writing a hand-made LCM log in a unit test: messages of one type on one channel, in order, or
// event by event.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace nerv::test {

// Appends one message as an event of `channel` at `timestamp` [us] to an open log.
template <typename T>
void appendLcmEvent(lcm::LogFile& log, const std::string& channel, const T& msg, int64_t timestamp,
                    int64_t eventnum = 0) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  lcm::LogEvent e{};
  e.eventnum = eventnum;
  e.timestamp = timestamp;
  e.channel = channel;
  e.datalen = static_cast<int32_t>(buf.size());
  e.data = buf.data();
  log.writeEvent(&e);
}

// False when the log cannot be written. Each message's event number is its index, its
// timestamp the index + 1 [us].
template <typename T>
bool writeLcmLog(const std::string& path, const std::string& channel, const std::vector<T>& messages) {
  lcm::LogFile log(path, "w");
  if (!log.good()) return false;
  for (size_t i = 0; i < messages.size(); ++i)
    appendLcmEvent(log, channel, messages[i], static_cast<int64_t>(i) + 1, static_cast<int64_t>(i));
  return true;
}

}  // namespace nerv::test

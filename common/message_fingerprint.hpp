// The fingerprint an LCM message begins with: its type's layout (8 bytes, big-endian). What
// tells a message of another layout or type from a broken one, and which type a logged event
// is, whatever its channel.
#pragma once

#include <cstdint>

namespace nerv {

// 0 when the message is shorter than a fingerprint.
inline int64_t messageFingerprint(const void* data, int64_t size) {
  if (!data || size < 8) return 0;
  const auto* b = static_cast<const uint8_t*>(data);
  uint64_t h = 0;
  for (int i = 0; i < 8; ++i) h = (h << 8) | b[i];
  return static_cast<int64_t>(h);
}

}  // namespace nerv

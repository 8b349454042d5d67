// Every nerv message as JSON with its .lcm field names, and decoding of a raw
// LCM payload by its type fingerprint (so channel prefixes do not matter).
#pragma once

#include <cstdint>
#include <string>

#include "json_writer.hpp"

namespace nerv {

// Decodes data as whichever nerv type its fingerprint names and writes it as a
// JSON object. Returns the type name ("nerv.stixels_t"), or "" when the payload
// is no nerv type or does not decode.
std::string writeMessageJson(const void* data, int size, JsonWriter& json);

}  // namespace nerv

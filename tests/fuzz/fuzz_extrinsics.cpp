// libFuzzer harness: bytes received as extrinsics_t, the way stixel (ground prior) takes them.
#include "fuzz_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return nerv::fuzz::harness(nerv::fuzz::receiveExtrinsics(data, size));
}

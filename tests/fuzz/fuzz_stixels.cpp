// libFuzzer harness: bytes received as stixels_t, the way snv_extrinsic, then validator takes them.
#include "fuzz_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return nerv::fuzz::harness(nerv::fuzz::receiveStixels(data, size));
}

// libFuzzer harness: bytes received as disparity_t, the way stixel, then snv_extrinsic takes them.
#include "fuzz_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return nerv::fuzz::harness(nerv::fuzz::receiveDisparity(data, size));
}

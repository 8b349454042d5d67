// libFuzzer harness: bytes received as stereo_frame_t, the way stereo_matcher takes them.
#include "fuzz_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return nerv::fuzz::harness(nerv::fuzz::receiveStereoFrame(data, size));
}

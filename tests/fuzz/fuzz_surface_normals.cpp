// libFuzzer harness: bytes received as surface_normals_t, the way validator takes them.
#include "fuzz_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return nerv::fuzz::harness(nerv::fuzz::receiveSurfaceNormals(data, size));
}

// The fallback of buildVersion() for programs built without the nerv_build_version
// object (unit tests, benchmarks, log tools): they relink on every commit otherwise,
// as every program did when the version lived in nerv_common (36 s of linking on 2
// cores for each commit or first edit). The services, nerv_up and nerv_source link
// the real one (common/build_version.cpp), which takes precedence over this weak one.
#include "build_version.hpp"

namespace nerv {

__attribute__((weak)) const char* buildVersion() { return "unknown (built without nerv_build_version)"; }

}  // namespace nerv

#include "build_version.hpp"

#include "nerv_version.hpp"  // generated into the build tree (cmake/NervVersion.cmake)

namespace nerv {

const char* buildVersion() { return NERV_VERSION; }

}  // namespace nerv

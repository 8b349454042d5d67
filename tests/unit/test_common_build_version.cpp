// buildVersion() (build_version.hpp): the project version and the source tree's
// `git describe`, as every service reports it in NERV_HEALTH and --version.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "build_version.hpp"

TEST(commonBuildVersion, NamesTheProjectVersionAndTheSourceTree) {
  const std::string v = nerv::buildVersion();
  EXPECT_TRUE(std::regex_match(v, std::regex(R"(\d+\.\d+\.\d+ \((no git|[0-9a-f]{7,}(-dirty)?|v?[0-9][^ ]*)\))")))
      << "'" << v << "'";
}

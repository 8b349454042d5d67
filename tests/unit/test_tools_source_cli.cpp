// nerv_source's rate cap (NERV_SOURCE_MAX_RATE, what `tools/nerv sanitize` sets for the
// multiprocess tests): a higher --rate is capped and said so, a lower one and --rate 0 are
// left alone, and a value that is not a rate above 0 is an error naming the variable.
// --check with --frames 0 returns before the source joins the bus, so nothing is sent.
#include <gtest/gtest.h>

#include "cli_run.hpp"

using namespace nerv::test;

namespace {
std::string source(const std::string& env, const std::string& args) {
  return runCli(env + " " + cliPath("nerv_source").string() + " " + args + " --frames 0 --check 2>&1; echo rc=$?");
}
}  // namespace

TEST(toolsSourceCli, AHigherRateIsCappedAndSaidSo) {
  const std::string out = source("NERV_SOURCE_MAX_RATE=1", "--rate 10");
  EXPECT_NE(out.find("source: --rate 10 capped at 1 Hz by NERV_SOURCE_MAX_RATE"), std::string::npos) << out;
  EXPECT_NE(out.find("rc=0"), std::string::npos) << out;
}

TEST(toolsSourceCli, LowerRatesAndAsFastAsAnsweredAreLeftAlone) {
  for (const char* args : {"--rate 0.5", "--rate 0", "--rate 10"}) {
    const std::string env = std::string(args) == "--rate 10" ? "NERV_SOURCE_MAX_RATE=" : "NERV_SOURCE_MAX_RATE=1";
    const std::string out = source(env, args);
    EXPECT_EQ(out.find("capped"), std::string::npos) << args << ": " << out;
    EXPECT_NE(out.find("rc=0"), std::string::npos) << args << ": " << out;
  }
}

TEST(toolsSourceCli, ACapThatIsNotARateIsAnError) {
  for (const char* bad : {"abc", "0", "-2", "nan", "inf", "2hz"}) {
    const std::string out = source(std::string("NERV_SOURCE_MAX_RATE=") + bad, "--rate 10");
    EXPECT_NE(out.find(std::string("NERV_SOURCE_MAX_RATE must be a rate above 0 Hz, not '") + bad + "'"), std::string::npos)
        << bad << ": " << out;
    EXPECT_NE(out.find("rc=2"), std::string::npos) << bad << ": " << out;
  }
}

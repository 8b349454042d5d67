// Running one of nerv's command-line tools from a unit test: where the binary is, its output.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace nerv::test {

// build/tests/test_x -> build/bin/<name>
inline std::filesystem::path cliPath(const std::string& name) {
  return std::filesystem::canonical("/proc/self/exe").parent_path().parent_path() / "bin" / name;
}

// What the command printed on standard output (add " 2>&1" for both).
inline std::string runCli(const std::string& cmd) {
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
  }
  return out;
}

// Runs of spaces as one, so the checks do not depend on column widths.
inline std::string squeezeSpaces(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != ' ' || out.empty() || out.back() != ' ') out += c;
  return out;
}

}  // namespace nerv::test

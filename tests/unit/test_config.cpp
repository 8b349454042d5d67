#include <gtest/gtest.h>

#include "config.hpp"

using namespace nerv;

namespace {
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(commonConfig, DefaultsStayWhenKeysAreAbsent) {
  ConfigSection c(YAML::Load("{}"), "stixel");
  int width = 5;
  double h = 2.5;
  std::string algo = "sgbm";
  c.get("column_width_px", width, 1, 64);
  c.get("max_height_m", h, 0, 10);
  c.get("algorithm", algo, {"sgbm", "bm"});
  c.finish();
  EXPECT_EQ(width, 5);
  EXPECT_EQ(h, 2.5);
  EXPECT_EQ(algo, "sgbm");
}

TEST(commonConfig, ValuesAreReadAndChecked) {
  ConfigSection c(YAML::Load("{a: 7, b: 0.5, s: bm, f: true}"), "x");
  int a = 0;
  double b = 0;
  std::string s;
  bool f = false;
  c.get("a", a, 1, 10);
  c.get("b", b, 0, 1);
  c.get("s", s, {"sgbm", "bm"});
  c.get("f", f);
  c.finish();
  EXPECT_EQ(a, 7);
  EXPECT_EQ(b, 0.5);
  EXPECT_EQ(s, "bm");
  EXPECT_TRUE(f);
}

TEST(commonConfig, UnknownKeyIsNamed) {
  ConfigSection c(YAML::Load("{column_width_px: 5, colum_width: 3}"), "stixel");
  int w = 0;
  c.get("column_width_px", w, 1, 64);
  EXPECT_EQ(errorOf([&] { c.finish(); }), "unknown config key 'stixel.colum_width'");
}

TEST(commonConfig, BadValuesAreNamed) {
  auto err = [](const char* yaml, auto apply) {
    return errorOf([&] {
      ConfigSection c(YAML::Load(yaml), "s");
      apply(c);
    });
  };
  EXPECT_NE(err("{n: 0}", [](ConfigSection& c) { int n = 1; c.get("n", n, 1, 9); }).find("'s.n' = 0 is outside"), std::string::npos);
  EXPECT_NE(err("{n: abc}", [](ConfigSection& c) { int n = 1; c.get("n", n); }).find("'s.n' must be an integer"), std::string::npos);
  EXPECT_NE(err("{x: .nan}", [](ConfigSection& c) { double x = 1; c.get("x", x); }).find("'s.x'"), std::string::npos);
  EXPECT_NE(err("{a: foo}", [](ConfigSection& c) { std::string a; c.get("a", a, {"bar", "baz"}); }).find("not one of: bar, baz"), std::string::npos);
  EXPECT_NE(err("{b: maybe}", [](ConfigSection& c) { bool b; c.get("b", b); }).find("true or false"), std::string::npos);
  EXPECT_NE(err("{m: [1, 2]}", [](ConfigSection& c) { int m; c.get("m", m); }).find("single value"), std::string::npos);
}

TEST(commonConfig, NestedSectionsCheckTheirOwnKeys) {
  ConfigSection root(YAML::Load("{shard: {index: 1, count: 2, extra: 1}}"), "");
  ConfigSection shard = root.section("shard");
  int index = 0, count = 1;
  shard.get("index", index, 0, 63);
  shard.get("count", count, 1, 64);
  root.finish();
  EXPECT_EQ(errorOf([&] { shard.finish(); }), "unknown config key 'shard.extra'");
}

TEST(commonConfig, MissingFileIsAnError) {
  EXPECT_NE(errorOf([] { loadConfigFile("/nonexistent/pipeline.yaml"); }).find("cannot be read"), std::string::npos);
  // A folder opens as a stream and fails only on reading: named as the file that cannot be read.
  const std::string folder = errorOf([] { loadConfigFile("/tmp"); });
  EXPECT_NE(folder.find("config file /tmp cannot be read: it is a folder"), std::string::npos) << folder;
}

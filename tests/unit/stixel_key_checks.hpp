// Shared check of the stixel tests: a key set to an out-of-range value is a
// ConfigError that names the key.
#pragma once

#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

#include "stixel_estimator.hpp"

namespace nerv::stixel {

inline void expectRejected(const char* key, double value) {
  YAML::Node bad;
  bad[key] = value;
  ConfigSection b(bad, "stixel");
  try {
    readParams(b);
    ADD_FAILURE() << key << " = " << value << " was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

// Each float key set to its value is read into its field, and each is rejected
// below its range (-1).
inline void expectFloatKeysRead(const std::vector<std::pair<const char*, float Params::*>>& keys,
                                const std::vector<double>& values) {
  ASSERT_EQ(keys.size(), values.size());
  YAML::Node n;
  for (size_t i = 0; i < keys.size(); ++i) n[keys[i].first] = values[i];
  ConfigSection c(n, "stixel");
  const Params p = readParams(c);
  EXPECT_NO_THROW(c.finish());
  for (size_t i = 0; i < keys.size(); ++i) {
    EXPECT_FLOAT_EQ(p.*keys[i].second, static_cast<float>(values[i])) << keys[i].first;
    expectRejected(keys[i].first, -1.0);
  }
}

}  // namespace nerv::stixel

// Shared check of the stixel tests: a key set to an out-of-range value is a
// ConfigError that names the key.
#pragma once

#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <string>

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

}  // namespace nerv::stixel

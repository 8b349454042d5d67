// YAML configuration with defaults in code. Every key a program reads is
// declared with its range; a key in the file that nobody declared, a value of
// the wrong type or out of range is a ConfigError whose message names the key.
#pragma once

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace nerv {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads a YAML file; a missing or unparsable file is a ConfigError.
YAML::Node loadConfigFile(const std::string& path);

class ConfigSection {
 public:
  // `node` may be undefined/null: every key then keeps its default.
  ConfigSection(YAML::Node node, std::string path);

  void get(const std::string& key, double& value,
           double lo = -std::numeric_limits<double>::infinity(),
           double hi = std::numeric_limits<double>::infinity());
  void get(const std::string& key, float& value,
           double lo = -std::numeric_limits<double>::infinity(),
           double hi = std::numeric_limits<double>::infinity());
  void get(const std::string& key, int& value, int lo = std::numeric_limits<int>::min(),
           int hi = std::numeric_limits<int>::max());
  void get(const std::string& key, bool& value);
  // With `allowed` non-empty the value must be one of them.
  void get(const std::string& key, std::string& value,
           std::initializer_list<const char*> allowed = {});
  // A nested map; its keys are checked by its own finish().
  ConfigSection section(const std::string& key);
  // Marks a key as known without reading it (it belongs to another program).
  void allow(const std::string& key);
  bool has(const std::string& key) const;
  // Throws ConfigError naming the first key that was never declared.
  void finish() const;

  const std::string& path() const { return path_; }

  // Every key read so far with its kind and range, for tests that walk a section's keys
  // (tests/unit/test_config_extremes.cpp): a value at either end of its range must run.
  struct Declared {
    enum Kind { kNumber, kInteger, kBool, kText } kind = kNumber;
    double lo = 0, hi = 0;              // kNumber, kInteger
    std::vector<std::string> allowed;   // kText (empty: any text)
  };
  const std::map<std::string, Declared>& declared() const { return declared_; }

 private:
  std::optional<YAML::Node> scalar(const std::string& key);
  std::string where(const std::string& key) const;
  YAML::Node node_;
  std::string path_;
  std::set<std::string> known_;
  std::map<std::string, Declared> declared_;
};

}  // namespace nerv

#include "config.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace nerv {

YAML::Node loadConfigFile(const std::string& path) {
  std::ifstream probe(path);
  if (!probe) throw ConfigError("config file " + path + " cannot be read");
  // A folder opens as a stream and fails only on reading, inside yaml-cpp (which then leaks its buffer).
  if (std::filesystem::is_directory(path)) throw ConfigError("config file " + path + " cannot be read: it is a folder");
  try {
    YAML::Node node = YAML::LoadFile(path);
    if (node.IsNull()) return YAML::Node(YAML::NodeType::Map);
    if (!node.IsMap()) throw ConfigError("config file " + path + " is not a YAML map");
    return node;
  } catch (const YAML::Exception& e) {
    throw ConfigError("config file " + path + ": " + e.msg + " at line " +
                      std::to_string(e.mark.line + 1));
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception& e) {  // the stream's own: a read that fails midway
    throw ConfigError("config file " + path + " cannot be read: " + e.what());
  }
}

ConfigSection::ConfigSection(YAML::Node node, std::string path)
    : node_(node), path_(std::move(path)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap())
    throw ConfigError("config key '" + path_ + "' must be a map");
}

std::string ConfigSection::where(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool ConfigSection::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

std::optional<YAML::Node> ConfigSection::scalar(const std::string& key) {
  known_.insert(key);
  if (!has(key)) return std::nullopt;
  YAML::Node v = node_[key];
  if (!v.IsScalar()) throw ConfigError("config key '" + where(key) + "' must be a single value");
  return v;
}

void ConfigSection::get(const std::string& key, double& value, double lo, double hi) {
  declared_[key] = {Declared::kNumber, lo, hi, {}};
  const std::optional<YAML::Node> found = scalar(key);
  if (!found) return;
  const YAML::Node& v = *found;
  double parsed;
  try {
    parsed = v.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError("config key '" + where(key) + "' must be a number, got '" +
                      v.Scalar() + "'");
  }
  if (!std::isfinite(parsed) || parsed < lo || parsed > hi) {
    std::ostringstream msg;
    msg << "config key '" << where(key) << "' = " << v.Scalar() << " is outside [" << lo << ", "
        << hi << "]";
    throw ConfigError(msg.str());
  }
  value = parsed;
}

void ConfigSection::get(const std::string& key, float& value, double lo, double hi) {
  double d = value;
  get(key, d, lo, hi);
  value = static_cast<float>(d);
}

void ConfigSection::get(const std::string& key, int& value, int lo, int hi) {
  declared_[key] = {Declared::kInteger, static_cast<double>(lo), static_cast<double>(hi), {}};
  const std::optional<YAML::Node> found = scalar(key);
  if (!found) return;
  const YAML::Node& v = *found;
  long long parsed;
  try {
    parsed = v.as<long long>();
  } catch (const YAML::Exception&) {
    throw ConfigError("config key '" + where(key) + "' must be an integer, got '" +
                      v.Scalar() + "'");
  }
  if (parsed < lo || parsed > hi) {
    std::ostringstream msg;
    msg << "config key '" << where(key) << "' = " << parsed << " is outside [" << lo << ", " << hi
        << "]";
    throw ConfigError(msg.str());
  }
  value = static_cast<int>(parsed);
}

void ConfigSection::get(const std::string& key, bool& value) {
  declared_[key] = {Declared::kBool, 0, 1, {}};
  const std::optional<YAML::Node> found = scalar(key);
  if (!found) return;
  const YAML::Node& v = *found;
  try {
    value = v.as<bool>();
  } catch (const YAML::Exception&) {
    throw ConfigError("config key '" + where(key) + "' must be true or false, got '" +
                      v.Scalar() + "'");
  }
}

void ConfigSection::get(const std::string& key, std::string& value,
                        std::initializer_list<const char*> allowed) {
  declared_[key] = {Declared::kText, 0, 0, std::vector<std::string>(allowed.begin(), allowed.end())};
  const std::optional<YAML::Node> found = scalar(key);
  if (!found) return;
  const YAML::Node& v = *found;
  const std::string s = v.Scalar();
  if (allowed.size() > 0) {
    bool ok = false;
    std::string list;
    for (const char* a : allowed) {
      ok = ok || s == a;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    if (!ok)
      throw ConfigError("config key '" + where(key) + "' = '" + s + "' is not one of: " + list);
  }
  value = s;
}

ConfigSection ConfigSection::section(const std::string& key) {
  known_.insert(key);
  return ConfigSection(has(key) ? node_[key] : YAML::Node(), where(key));
}

void ConfigSection::allow(const std::string& key) { known_.insert(key); }

void ConfigSection::finish() const {
  if (!node_.IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (!known_.count(key)) throw ConfigError("unknown config key '" + where(key) + "'");
  }
}

}  // namespace nerv

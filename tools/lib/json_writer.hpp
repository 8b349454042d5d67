// A small streaming JSON writer: objects, arrays, numbers, strings, and byte
// arrays as base64 (or just their length when blobs are not wanted).
#pragma once

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace nerv {

class JsonWriter {
 public:
  explicit JsonWriter(bool with_blobs = true) : with_blobs_(with_blobs) {}

  void beginObject() { separate(); out_ << '{'; first_ = true; }
  void endObject() { out_ << '}'; first_ = false; }
  void beginArray() { separate(); out_ << '['; first_ = true; }
  void endArray() { out_ << ']'; first_ = false; }
  void key(const std::string& k) { separate(); string(k); out_ << ':'; first_ = true; }

  void value(bool v) { separate(); out_ << (v ? "true" : "false"); }
  void value(const std::string& v) { separate(); string(v); }
  void value(const char* v) { value(std::string(v)); }
  template <class T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  void value(T v) { separate(); out_ << static_cast<long long>(v); }
  template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
  void value(T v) {
    separate();
    if (std::isfinite(v)) {
      std::ostringstream s;
      s.precision(std::is_same_v<T, float> ? 9 : 17);
      s << v;
      out_ << s.str();
    } else {
      out_ << "null";  // JSON has no NaN/inf
    }
  }
  // byte arrays
  void value(const std::vector<uint8_t>& bytes);

  template <class T>
  void field(const std::string& k, const T& v) { key(k); value(v); }

  std::string str() const { return out_.str(); }

 private:
  void separate() {
    if (!first_) out_ << ',';
    first_ = false;
  }
  void string(const std::string& s);
  std::ostringstream out_;
  bool first_ = true;
  bool with_blobs_;
};

}  // namespace nerv

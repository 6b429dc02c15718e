#pragma once
// A streaming JSON writer into one string: the bridge's large messages (a thousand robots five
// times a second, megabytes of base64) cost a fraction of what building a DOM first would.
// Commas are placed by the writer; keys and values must alternate inside objects.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace slam::bridge {

class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : out_(out) {}

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view k);
  JsonWriter& value(std::string_view s);
  JsonWriter& value(const char* s) { return value(std::string_view(s)); }
  // Shortest text that reads back as the same double; a non-finite value (never valid JSON) as 0.
  JsonWriter& value(double d);
  JsonWriter& value(int64_t i);
  JsonWriter& value(int i) { return value(static_cast<int64_t>(i)); }
  JsonWriter& value(uint32_t i) { return value(static_cast<int64_t>(i)); }
  JsonWriter& value(bool b);
  JsonWriter& base64_value(std::span<const uint8_t> bytes);
  // An empty array under `k`.
  JsonWriter& empty_array(std::string_view k) { return key(k).begin_array().end_array(); }

 private:
  void separate();

  std::string& out_;
  std::vector<bool> first_{true};  // per open container: nothing written in it yet
  bool after_key_ = false;
};

}  // namespace slam::bridge

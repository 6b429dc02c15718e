#pragma once
// Base64 (RFC 4648, with padding): JSON-encoded Foxglove messages carry bytes (grid cells, point
// data) as base64 strings.
#include <cstdint>
#include <span>
#include <string>

namespace slam::bridge {

// Appends the base64 text of `bytes` to `out`.
void append_base64(std::span<const uint8_t> bytes, std::string& out);

inline std::string base64(std::span<const uint8_t> bytes) {
  std::string out;
  append_base64(bytes, out);
  return out;
}

}  // namespace slam::bridge

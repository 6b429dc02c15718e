// Hex and v1 payload text for the MQTT tab (see payload_text.hpp).
#include "viewer/core/payload_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>

namespace slam::viewer {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

int16_t read_i16(std::span<const uint8_t> b, size_t at) {
  return static_cast<int16_t>(static_cast<uint16_t>(b[at] | (b[at + 1] << 8)));
}

// Well-formed UTF-8 without control characters other than tab and newlines.
bool printable_utf8(std::span<const uint8_t> b) {
  for (size_t i = 0; i < b.size();) {
    const uint8_t c = b[i];
    size_t extra = 0;
    if (c < 0x80) {
      if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return false;
      if (c == 0x7f) return false;
    } else if ((c & 0xe0) == 0xc0) {
      extra = 1;
    } else if ((c & 0xf0) == 0xe0) {
      extra = 2;
    } else if ((c & 0xf8) == 0xf0) {
      extra = 3;
    } else {
      return false;
    }
    if (extra > 0 && i + extra >= b.size()) return false;
    for (size_t k = 1; k <= extra; ++k)
      if ((b[i + k] & 0xc0) != 0x80) return false;
    i += 1 + extra;
  }
  return true;
}

}  // namespace

std::string to_hex(std::span<const uint8_t> bytes, size_t max_bytes) {
  const size_t n = std::min(bytes.size(), max_bytes);
  std::string out;
  out.reserve(n * 3 + 16);
  char buf[4];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, i + 1 < n ? "%02x " : "%02x", bytes[i]);
    out += buf;
  }
  if (n < bytes.size()) out += " ...(+" + std::to_string(bytes.size() - n) + ")";
  return out;
}

Result<std::vector<uint8_t>> parse_hex(std::string_view text) {
  std::vector<uint8_t> out;
  int high = -1;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
      if (high >= 0) return Error{"odd hex digit before offset " + std::to_string(i)};
      continue;
    }
    if (c == '0' && high < 0 && i + 1 < text.size() && (text[i + 1] == 'x' || text[i + 1] == 'X')) {
      ++i;
      continue;
    }
    const int v = hex_value(c);
    if (v < 0) return Error{std::string("not a hex digit '") + c + "' at offset " + std::to_string(i)};
    if (high < 0) {
      high = v;
    } else {
      out.push_back(static_cast<uint8_t>(high * 16 + v));
      high = -1;
    }
  }
  if (high >= 0) return Error{"odd number of hex digits"};
  return out;
}

Result<std::vector<uint8_t>> encode_v1_pairs(const std::vector<std::pair<long, long>>& pairs) {
  if (pairs.empty()) return Error{"a v1 message needs at least one (x, y) pair"};
  std::vector<uint8_t> out;
  out.reserve(pairs.size() * 4);
  for (size_t i = 0; i < pairs.size(); ++i) {
    for (long v : {pairs[i].first, pairs[i].second}) {
      if (v < -32768 || v > 32767)
        return Error{"pair " + std::to_string(i) + " value " + std::to_string(v) + " is outside int16"};
      const auto u = static_cast<uint16_t>(static_cast<int16_t>(v));
      out.push_back(static_cast<uint8_t>(u & 0xff));
      out.push_back(static_cast<uint8_t>(u >> 8));
    }
  }
  return out;
}

Result<std::vector<std::pair<long, long>>> parse_pairs(std::string_view text) {
  std::vector<long> values;
  const char* p = text.data();
  const char* end = p + text.size();
  while (p < end) {
    if (std::isspace(static_cast<unsigned char>(*p)) || *p == ',' || *p == '(' || *p == ')') {
      ++p;
      continue;
    }
    long v = 0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc{}) return Error{"not a number at offset " + std::to_string(p - text.data())};
    values.push_back(v);
    p = next;
  }
  if (values.empty() || values.size() % 2 != 0) return Error{"expected x,y pairs (an even count of numbers)"};
  std::vector<std::pair<long, long>> pairs;
  for (size_t i = 0; i < values.size(); i += 2) pairs.emplace_back(values[i], values[i + 1]);
  return pairs;
}

std::string decode_payload(std::string_view topic, std::span<const uint8_t> bytes) {
  const bool v1 = topic.substr(0, 3) == "v1/";
  if (v1 && ends_with(topic, "/adv") && !bytes.empty() && bytes.size() % 4 == 0) {
    std::string out =
        "pos (" + std::to_string(read_i16(bytes, 0)) + ", " + std::to_string(read_i16(bytes, 2)) + ")";
    const size_t pairs = bytes.size() / 4;
    out += "; " + std::to_string(pairs - 1) + " obstacles:";
    const size_t shown = std::min<size_t>(pairs, 33);
    for (size_t i = 1; i < shown; ++i)
      out += " (" + std::to_string(read_i16(bytes, 4 * i)) + ", " +
             std::to_string(read_i16(bytes, 4 * i + 2)) + ")";
    if (shown < pairs) out += " ...";
    return out;
  }
  if (v1 && ends_with(topic, "/cmd") && bytes.size() == 4)
    return "waypoint (" + std::to_string(read_i16(bytes, 0)) + ", " + std::to_string(read_i16(bytes, 2)) +
           ")";
  if (printable_utf8(bytes)) return std::string(bytes.begin(), bytes.end());
  return to_hex(bytes);
}

}  // namespace slam::viewer

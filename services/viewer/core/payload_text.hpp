#pragma once
// MQTT payloads as operators read and type them: hex dumps, hex parsing for raw publishes, and
// the 2019 v1 format (little-endian int16 pairs) decoded for display and encoded for test
// messages, so the MQTT tab can show "what the robot said" next to the bytes.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/core/result.hpp"

namespace slam::viewer {

// "0a ff 10 ..." for at most `max_bytes` octets, with "…(+N)" when cut.
std::string to_hex(std::span<const uint8_t> bytes, size_t max_bytes = 1024);

// Parses hex octets; whitespace, commas and "0x" prefixes are ignored. Errors name the offset.
Result<std::vector<uint8_t>> parse_hex(std::string_view text);

// v1 payload: (x, y) int16 LE pairs, checked for range (never wrapped).
Result<std::vector<uint8_t>> encode_v1_pairs(const std::vector<std::pair<long, long>>& pairs);
// Parses "x,y x,y ..." (robot units) into pairs for encode_v1_pairs.
Result<std::vector<std::pair<long, long>>> parse_pairs(std::string_view text);

// Human-readable form: v1 robot/server messages by topic, printable UTF-8 text as is, otherwise hex.
std::string decode_payload(std::string_view topic, std::span<const uint8_t> bytes);

}  // namespace slam::viewer

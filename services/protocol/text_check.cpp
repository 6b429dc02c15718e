// Strict UTF-8 and control-character scan, written against the Unicode "well-formed byte
// sequences" table so overlong forms and surrogates are refused, not just counted.
#include "protocol/text_check.hpp"

#include <cstdint>

namespace slam::protocol {
namespace {

// Length of the well-formed sequence starting at text[i], or 0 if ill-formed.
std::size_t sequence_length(std::string_view text, std::size_t i) {
  auto byte = [&](std::size_t k) { return static_cast<std::uint8_t>(text[k]); };
  const std::uint8_t b0 = byte(i);
  const std::size_t left = text.size() - i;
  auto cont = [&](std::size_t k, std::uint8_t lo = 0x80, std::uint8_t hi = 0xBF) {
    return k < left && byte(i + k) >= lo && byte(i + k) <= hi;
  };
  if (b0 < 0x80) return 1;
  if (b0 >= 0xC2 && b0 <= 0xDF) return cont(1) ? 2 : 0;
  if (b0 == 0xE0) return cont(1, 0xA0) && cont(2) ? 3 : 0;        // no overlongs
  if (b0 == 0xED) return cont(1, 0x80, 0x9F) && cont(2) ? 3 : 0;  // no surrogates
  if (b0 >= 0xE1 && b0 <= 0xEF) return cont(1) && cont(2) ? 3 : 0;
  if (b0 == 0xF0) return cont(1, 0x90) && cont(2) && cont(3) ? 4 : 0;
  if (b0 >= 0xF1 && b0 <= 0xF3) return cont(1) && cont(2) && cont(3) ? 4 : 0;
  if (b0 == 0xF4) return cont(1, 0x80, 0x8F) && cont(2) && cont(3) ? 4 : 0;  // <= U+10FFFF
  return 0;
}

}  // namespace

std::optional<TextProblem> find_text_problem(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t n = sequence_length(text, i);
    if (n == 0) return TextProblem{i, "invalid UTF-8"};
    const auto b0 = static_cast<std::uint8_t>(text[i]);
    const bool c0_or_del = n == 1 && (b0 < 0x20 || b0 == 0x7F);
    const bool c1 = n == 2 && b0 == 0xC2 && static_cast<std::uint8_t>(text[i + 1]) <= 0x9F;
    if (c0_or_del || c1) return TextProblem{i, "control character"};
    i += n;
  }
  return std::nullopt;
}

}  // namespace slam::protocol

namespace slam::protocol {

std::string escape_for_log(std::string_view text, std::size_t max_bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  const std::size_t n = text.size() < max_bytes ? text.size() : max_bytes;
  out.reserve(n + 3);
  for (std::size_t i = 0; i < n; ++i) {
    const auto b = static_cast<std::uint8_t>(text[i]);
    if (b >= 0x20 && b < 0x7F && b != '\\') {
      out += static_cast<char>(b);
    } else {
      out += "\\x";
      out += kHex[b >> 4];
      out += kHex[b & 0x0F];
    }
  }
  if (n < text.size()) out += "...";
  return out;
}

}  // namespace slam::protocol

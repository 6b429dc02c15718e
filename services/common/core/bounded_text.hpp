#pragma once
// IDL strings are bounded (string<64>, char[65] in C): text from the network or the command line is
// cut to fit. One rule for every service: cut at a character boundary, so a bounded copy of valid
// UTF-8 is still valid UTF-8 (a robot id in a log line, a world name in the viewer).
#include <cstddef>
#include <string_view>

namespace slam {

// The longest prefix of `text` of at most `max_bytes` bytes that does not end inside a UTF-8
// multi-byte character.
inline std::string_view bounded_prefix(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return text;
  std::size_t n = max_bytes;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
  return text.substr(0, n);
}

}  // namespace slam

#include "common/core/mcap_records.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstring>

namespace slam::mcap {

void Encoder::raw(std::span<const uint8_t> b) {
  if (b.empty()) return;
  // resize + memcpy rather than insert: GCC 12 warns falsely (-Wstringop-overflow) on the insert.
  const size_t at = bytes_.size();
  bytes_.resize(at + b.size());
  std::memcpy(bytes_.data() + at, b.data(), b.size());
}

void Encoder::prefixed(std::string_view s) {
  u32(static_cast<uint32_t>(s.size()));
  raw({reinterpret_cast<const uint8_t*>(s.data()), s.size()});
}

void Encoder::string_map(const std::map<std::string, std::string>& m) {
  Encoder entries;
  for (const auto& [key, value] : m) {
    entries.prefixed(key);
    entries.prefixed(value);
  }
  u32(static_cast<uint32_t>(entries.bytes().size()));
  raw(entries.bytes());
}

void Encoder::record(Opcode op, std::span<const uint8_t> content) {
  u8(static_cast<uint8_t>(op));
  u64(content.size());
  raw(content);
}

uint32_t crc32(std::span<const uint8_t> bytes, uint32_t crc) {
  // zlib takes uInt lengths: feed large spans in pieces.
  constexpr size_t kPiece = size_t{1} << 30;
  uLong value = crc;
  for (size_t at = 0; at < bytes.size(); at += kPiece) {
    const size_t n = std::min(kPiece, bytes.size() - at);
    value = ::crc32(value, bytes.data() + at, static_cast<uInt>(n));
  }
  return static_cast<uint32_t>(value);
}

}  // namespace slam::mcap

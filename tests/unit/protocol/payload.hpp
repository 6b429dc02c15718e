#pragma once
// Test helper: view text or byte lists as the payload spans the codecs take.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace slam::protocol::test {

inline std::span<const std::uint8_t> bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

}  // namespace slam::protocol::test

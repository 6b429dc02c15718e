#pragma once
// The input of the MQTT decoders' fuzz targets: "<topic>\n<payload>" (no newline: a topic and no payload).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace slam::fuzz {

struct TopicInput {
  std::string_view topic;
  std::span<const std::uint8_t> payload;
};

inline TopicInput split_topic_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t newline = input.find('\n');
  if (newline == std::string_view::npos) return {input, {}};
  return {input.substr(0, newline), std::span(data + newline + 1, size - newline - 1)};
}

}  // namespace slam::fuzz

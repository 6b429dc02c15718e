// Fuzz target for the MCAP reader: any input either fails with a message or parses into contents
// whose every message names a known channel, every channel a known schema (or none), and whose
// message data lies inside the input. Nothing may crash, hang or allocate unboundedly.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "common/core/mcap_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::span<const uint8_t> input(data, size);
  auto contents = slam::mcap::parse(input);
  if (!contents) {
    if (contents.message().empty()) std::abort();
    return 0;
  }
  for (const auto& [id, channel] : contents->channels)
    if (channel.id != id || (channel.schema_id != 0 && !contents->schemas.contains(channel.schema_id)))
      std::abort();
  for (const slam::mcap::MessageView& m : contents->messages) {
    if (!contents->channels.contains(m.channel_id)) std::abort();
    if (!m.data.empty() && (m.data.data() < data || m.data.data() + m.data.size() > data + size))
      std::abort();
  }
  if (contents->statistics && contents->statistics->message_count != contents->messages.size()) std::abort();
  return 0;
}

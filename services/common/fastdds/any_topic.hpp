#pragma once
// Every topic of the table (fast_topics.hpp) behind one type-erased interface that reads and writes
// CDR bytes exactly as Fast DDS puts them on the wire (encapsulation header, then the data): for tools
// that treat all topics alike, e.g. `slamctl record` and `slamctl replay`.
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/fastdds/fast_topics.hpp"

namespace slam::dds {

// The wire bytes of `sample`; empty when the type support refused it.
template <class PubSubT, class T>
std::vector<uint8_t> to_cdr(const T& sample) {
  PubSubT type;
  auto* data = const_cast<T*>(&sample);  // the type support takes void* but only reads
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(data)());
  if (!type.serialize(data, &payload)) return {};
  return {payload.data, payload.data + payload.length};
}

// Decodes wire bytes into `out`; false when they do not hold a T.
template <class PubSubT, class T>
bool from_cdr(std::span<const uint8_t> cdr, T& out) {
  PubSubT type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(cdr.size()));
  if (!cdr.empty()) std::memcpy(payload.data, cdr.data(), cdr.size());
  payload.length = static_cast<uint32_t>(cdr.size());
  try {
    return type.deserialize(&payload, &out);
  } catch (...) {  // fastcdr throws on bounds it checks (bounded strings, bad sequence lengths)
    return false;
  }
}

// Writes samples given as wire bytes (decoded into the topic's type, then written as usual).
class CdrWriter {
 public:
  virtual ~CdrWriter() = default;
  virtual Status write(std::span<const uint8_t> cdr) = 0;
  virtual int matched_readers() const = 0;
  virtual bool wait_for_acknowledgments(std::chrono::milliseconds timeout) = 0;
};

// Hands every sample to its callback as wire bytes, on the middleware's listener thread.
class CdrReader {
 public:
  virtual ~CdrReader() = default;
  virtual int matched_writers() const = 0;
};

using CdrCallback = std::function<void(std::span<const uint8_t> cdr, const fdds::SampleInfo& info)>;

struct AnyTopic {
  topics::TopicInfo info;
  std::string type_name;  // fully qualified IDL name, e.g. "slam::RobotState"
  std::function<Result<std::unique_ptr<CdrReader>>(Participant&, CdrCallback)> make_reader;
  std::function<Result<std::unique_ptr<CdrWriter>>(Participant&)> make_writer;
};

// Every topic of fast_topics.hpp.
const std::vector<AnyTopic>& all_topics();
// The topic called `name`, or nullptr.
const AnyTopic* find_topic(std::string_view name);

}  // namespace slam::dds

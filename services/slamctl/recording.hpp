#pragma once
// The DDS-free part of `slamctl record` and `slamctl replay`: the recorder that turns samples (CDR
// bytes per topic) into an MCAP file Foxglove opens, which topics a --topics list selects, and which
// channels of a recording go back onto which topics, at what time.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/mcap_reader.hpp"
#include "common/core/mcap_writer.hpp"

namespace slam::ctl {

// Channel message encoding and schema encoding of every recorded topic.
inline constexpr std::string_view kMessageEncoding = "cdr";
inline constexpr std::string_view kSchemaEncoding = "omgidl";

struct RecordingStats {
  uint64_t messages = 0;
  uint64_t bytes = 0;  // file size so far
  size_t topics = 0;   // topics that had a sample
};

// Writes samples to an MCAP file: on a topic's first sample, its schema (the type's IDL, named by
// the fully qualified type name) and a channel; then a Message per sample. Safe to call from several
// threads (DDS listener threads). After the first failure (e.g. disk full) it records nothing more
// and close() reports that failure.
class SessionRecorder {
 public:
  static Result<std::unique_ptr<SessionRecorder>> create(const std::string& path);

  // log_time: when the sample was received; publish_time: when its writer stamped it (ns since epoch).
  void add(std::string_view topic, std::string_view type_name, std::span<const uint8_t> cdr,
           uint64_t log_time, uint64_t publish_time);
  RecordingStats stats() const;
  // True once a sample could not be recorded (close() says why).
  bool failed() const;
  // Ends the file (summary, footer): the file is valid only after this.
  Status close();

 private:
  explicit SessionRecorder(std::unique_ptr<mcap::Writer> writer) : writer_(std::move(writer)) {}
  Result<uint16_t> channel_for(std::string_view topic, std::string_view type_name);

  mutable std::mutex mutex_;
  std::unique_ptr<mcap::Writer> writer_;
  std::map<std::string, uint16_t, std::less<>> channels_;  // topic -> channel id
  Status failure_;
};

// The topics a comma-separated list names (all of `available` when empty); an unknown name is an
// error.
Result<std::vector<std::string>> select_topics(std::string_view comma_list,
                                               const std::vector<std::string>& available);

// Which channels of a recording replay onto which topics.
struct ReplayPlan {
  std::map<uint16_t, std::string> topic_of;  // channel id -> topic
  std::vector<std::string> skipped;          // one line per channel left out, saying why
};

// A channel replays when its topic is one of `type_of` (topic -> fully qualified type name) with the
// same type as its schema, CDR-encoded, and in `selected` (every topic when empty).
ReplayPlan plan_replay(const mcap::Contents& recording, const std::map<std::string, std::string>& type_of,
                       const std::vector<std::string>& selected);

// When a message logged at `log_time` goes out, counted from the replay's start: the recorded delay
// after `first_log_time`, divided by `rate` (earlier messages go at once).
std::chrono::nanoseconds replay_offset(uint64_t first_log_time, uint64_t log_time, double rate);

}  // namespace slam::ctl

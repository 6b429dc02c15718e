#include "slamctl/recording.hpp"

#include <algorithm>
#include <cmath>

#include "common/core/idl_text.hpp"

namespace slam::ctl {

Result<std::unique_ptr<SessionRecorder>> SessionRecorder::create(const std::string& path) {
  auto writer = mcap::Writer::create(path, "slamfleet slamctl");
  if (!writer) return writer.error();
  return std::unique_ptr<SessionRecorder>(new SessionRecorder(std::move(*writer)));
}

Result<uint16_t> SessionRecorder::channel_for(std::string_view topic, std::string_view type_name) {
  if (auto it = channels_.find(topic); it != channels_.end()) return it->second;
  auto idl = omgidl_schema(type_name);
  if (!idl) return idl.error();
  auto schema = writer_->add_schema(type_name, kSchemaEncoding, *idl);
  if (!schema) return schema.error();
  auto channel = writer_->add_channel(*schema, topic, kMessageEncoding);
  if (!channel) return channel.error();
  channels_.emplace(std::string(topic), *channel);
  return *channel;
}

void SessionRecorder::add(std::string_view topic, std::string_view type_name, std::span<const uint8_t> cdr,
                          uint64_t log_time, uint64_t publish_time) {
  std::lock_guard lock(mutex_);
  if (!failure_) return;
  auto channel = channel_for(topic, type_name);
  if (!channel) {
    failure_ = channel.error();
    return;
  }
  failure_ = writer_->write_message(*channel, log_time, publish_time, cdr);
}

RecordingStats SessionRecorder::stats() const {
  std::lock_guard lock(mutex_);
  return {writer_->message_count(), writer_->bytes_written(), channels_.size()};
}

bool SessionRecorder::failed() const {
  std::lock_guard lock(mutex_);
  return !failure_;
}

Status SessionRecorder::close() {
  std::lock_guard lock(mutex_);
  // Even after a failure, try to end the file so what was recorded stays readable.
  Status closed = writer_->close();
  if (!failure_) return failure_;
  return closed;
}

Result<std::vector<std::string>> select_topics(std::string_view comma_list,
                                               const std::vector<std::string>& available) {
  if (comma_list.empty()) return available;
  std::vector<std::string> selected;
  size_t from = 0;
  while (from <= comma_list.size()) {
    const size_t comma = std::min(comma_list.find(',', from), comma_list.size());
    const std::string name(comma_list.substr(from, comma - from));
    from = comma + 1;
    if (name.empty()) continue;
    if (std::find(available.begin(), available.end(), name) == available.end())
      return Error{"unknown topic '" + name + "' (see docs/topics.md)"};
    selected.push_back(name);
  }
  if (selected.empty()) return Error{"--topics names no topic"};
  return selected;
}

ReplayPlan plan_replay(const mcap::Contents& recording, const std::map<std::string, std::string>& type_of,
                       const std::vector<std::string>& selected) {
  ReplayPlan plan;
  for (const auto& [id, channel] : recording.channels) {
    const std::string label = "skipping channel '" + channel.topic + "': ";
    if (!selected.empty() && std::find(selected.begin(), selected.end(), channel.topic) == selected.end())
      continue;  // not asked for: no line
    auto type = type_of.find(channel.topic);
    if (type == type_of.end()) {
      plan.skipped.push_back(label + "not a topic of this system");
      continue;
    }
    auto schema = recording.schemas.find(channel.schema_id);
    if (channel.message_encoding != kMessageEncoding || schema == recording.schemas.end() ||
        schema->second.encoding != kSchemaEncoding) {
      plan.skipped.push_back(label + "not CDR with an omgidl schema");
      continue;
    }
    if (schema->second.name != type->second) {
      plan.skipped.push_back(label + "recorded as " + schema->second.name + ", the topic's type is " +
                             type->second);
      continue;
    }
    plan.topic_of.emplace(id, channel.topic);
  }
  return plan;
}

std::chrono::nanoseconds replay_offset(uint64_t first_log_time, uint64_t log_time, double rate) {
  if (log_time <= first_log_time) return std::chrono::nanoseconds(0);
  return std::chrono::nanoseconds(
      static_cast<int64_t>(std::llround(static_cast<double>(log_time - first_log_time) / rate)));
}

}  // namespace slam::ctl

#pragma once
// The MQTT tab's message log: newest last, bounded both in entries and in bytes so a flood of
// large payloads cannot grow the viewer's memory; evictions are counted and shown.
#include <cstddef>
#include <cstdint>
#include <deque>

#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

class MqttLog {
 public:
  MqttLog(size_t max_entries = 5000, size_t max_bytes = size_t{8} << 20)
      : max_entries_(max_entries), max_bytes_(max_bytes) {}

  void push(MqttEntry&& e);
  void clear();

  size_t size() const { return entries_.size(); }
  const MqttEntry& at(size_t i) const { return entries_[i]; }  // 0 = oldest kept
  size_t bytes() const { return bytes_; }
  uint64_t evicted() const { return evicted_; }
  uint64_t inbound() const { return inbound_; }
  uint64_t outbound() const { return outbound_; }
  size_t max_entries() const { return max_entries_; }
  size_t max_bytes() const { return max_bytes_; }

  // Memory an entry is charged with: its strings and payload plus the bookkeeping.
  static size_t cost(const MqttEntry& e) { return sizeof(MqttEntry) + e.topic.size() + e.payload.size(); }

 private:
  size_t max_entries_;
  size_t max_bytes_;
  std::deque<MqttEntry> entries_;
  size_t bytes_ = 0;
  uint64_t evicted_ = 0;
  uint64_t inbound_ = 0;
  uint64_t outbound_ = 0;
};

}  // namespace slam::viewer

#pragma once
// The MQTT traffic log for the viewer, decoupled from the hot path: the MQTT callback copies a
// record into a preallocated ring (no allocation, one short lock) and a worker drains it into DDS.
// The log is rate-limited and bounded: beyond the rate or when the ring is full a record is
// dropped and counted, so a flood of messages can never stall the gateway or grow its memory.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace slam::gateway {

inline constexpr std::size_t kTrafficTopicBytes = 256;     // IDL MqttTraffic.topic bound
inline constexpr std::size_t kTrafficPayloadBytes = 1024;  // IDL MqttTraffic.payload bound

enum class TrafficDirection : std::uint8_t { Inbound, Outbound };

struct TrafficRecord {
  std::uint64_t seq = 0;  // counts every message offered, dropped ones too: gaps show drops
  std::int64_t stamp_ns = 0;
  TrafficDirection direction = TrafficDirection::Inbound;
  std::string topic;                  // cut to kTrafficTopicBytes
  std::vector<std::uint8_t> payload;  // cut to kTrafficPayloadBytes
  std::uint32_t payload_size = 0;     // the real size
};

// `rate` tokens per second, at most `burst` saved up. Time is passed in, so tests need no clock.
class TokenBucket {
 public:
  TokenBucket(double rate_per_s, double burst)
      : rate_per_ns_(rate_per_s * 1e-9), burst_(burst), tokens_(burst) {}
  bool take(std::int64_t mono_ns);

 private:
  double rate_per_ns_;
  double burst_;
  double tokens_;
  std::int64_t last_ns_ = 0;
  bool started_ = false;
};

class TrafficQueue {
 public:
  TrafficQueue(std::size_t capacity, double rate_per_s);

  // Copies one message in; false when it was dropped (over the rate, or the ring is full).
  bool push(TrafficDirection direction, std::string_view topic, std::span<const std::uint8_t> payload,
            std::int64_t stamp_ns, std::int64_t mono_ns);
  // Waits up to `timeout` for a full batch (batch.size() records), then swaps up to that many
  // into `batch` (whose buffers go back into the ring, so neither side allocates). Returns how
  // many were taken. Only a full batch wakes the waiting worker early: a wake per record would
  // cost the gateway a thread switch per MQTT message.
  std::size_t pop(std::vector<TrafficRecord>& batch, std::chrono::milliseconds timeout);
  // A batch sized and reserved like the ring's slots.
  std::vector<TrafficRecord> make_batch(std::size_t size) const;
  // Wakes a waiting pop() for good (shutdown).
  void close();

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<TrafficRecord> ring_;
  std::size_t head_ = 0;  // oldest record
  std::size_t count_ = 0;
  std::size_t wake_at_ = 1;  // records that wake a waiting pop(): its batch size
  std::uint64_t next_seq_ = 1;
  TokenBucket bucket_;
  bool closed_ = false;
};

}  // namespace slam::gateway

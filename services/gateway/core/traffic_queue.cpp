// TrafficQueue: token bucket in front of a fixed ring of preallocated records.
#include "gateway/core/traffic_queue.hpp"

#include <algorithm>
#include <utility>

namespace slam::gateway {

namespace {

void reserve_record(TrafficRecord& r) {
  r.topic.reserve(kTrafficTopicBytes);
  r.payload.reserve(kTrafficPayloadBytes);
}

}  // namespace

bool TokenBucket::take(std::int64_t mono_ns) {
  if (!started_) {
    started_ = true;
    last_ns_ = mono_ns;
  }
  if (mono_ns > last_ns_) {
    tokens_ = std::min(burst_, tokens_ + static_cast<double>(mono_ns - last_ns_) * rate_per_ns_);
    last_ns_ = mono_ns;
  }
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

TrafficQueue::TrafficQueue(std::size_t capacity, double rate_per_s)
    : ring_(std::max<std::size_t>(capacity, 1)),
      // A tenth of a second's worth saved up lets short bursts through whole; rate 0 turns it off.
      bucket_(rate_per_s, rate_per_s > 0.0 ? std::max(1.0, rate_per_s / 10.0) : 0.0) {
  for (TrafficRecord& r : ring_) reserve_record(r);
}

std::vector<TrafficRecord> TrafficQueue::make_batch(std::size_t size) const {
  std::vector<TrafficRecord> batch(size);
  for (TrafficRecord& r : batch) reserve_record(r);
  return batch;
}

bool TrafficQueue::push(TrafficDirection direction, std::string_view topic,
                        std::span<const std::uint8_t> payload, std::int64_t stamp_ns, std::int64_t mono_ns) {
  {
    std::lock_guard lock(mutex_);
    const std::uint64_t seq = next_seq_++;
    if (closed_ || !bucket_.take(mono_ns) || count_ == ring_.size()) return false;
    TrafficRecord& r = ring_[(head_ + count_) % ring_.size()];
    r.seq = seq;
    r.stamp_ns = stamp_ns;
    r.direction = direction;
    r.topic.assign(topic.substr(0, kTrafficTopicBytes));
    const std::size_t kept = std::min(payload.size(), kTrafficPayloadBytes);
    r.payload.assign(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(kept));
    r.payload_size = static_cast<std::uint32_t>(std::min<std::size_t>(payload.size(), UINT32_MAX));
    if (++count_ != wake_at_) return true;
  }
  ready_.notify_one();
  return true;
}

std::size_t TrafficQueue::pop(std::vector<TrafficRecord>& batch, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  wake_at_ = std::max<std::size_t>(1, std::min(batch.size(), ring_.size()));
  ready_.wait_for(lock, timeout, [&] { return count_ >= wake_at_ || closed_; });
  const std::size_t n = std::min(count_, batch.size());
  for (std::size_t i = 0; i < n; ++i) {
    std::swap(batch[i], ring_[head_]);
    head_ = (head_ + 1) % ring_.size();
  }
  count_ -= n;
  return n;
}

void TrafficQueue::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

}  // namespace slam::gateway

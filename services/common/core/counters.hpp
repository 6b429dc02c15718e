#pragma once
// Named monotonic counters a service increments on hot paths (one relaxed atomic add) and the
// heartbeat reads. Counter references stay valid for the registry's lifetime.
#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace slam {

class Counters {
 public:
  // Returns the counter called `name`, creating it at zero. Call at set-up, keep the reference.
  std::atomic<int64_t>& get(const std::string& name) {
    std::lock_guard lock(mutex_);
    for (auto& [n, value] : entries_)
      if (n == name) return value;
    return entries_
        .emplace_back(std::piecewise_construct, std::forward_as_tuple(name), std::forward_as_tuple(0))
        .second;
  }

  std::vector<std::pair<std::string, int64_t>> snapshot() const {
    std::lock_guard lock(mutex_);
    std::vector<std::pair<std::string, int64_t>> out;
    out.reserve(entries_.size());
    for (const auto& [n, value] : entries_) out.emplace_back(n, value.load(std::memory_order_relaxed));
    return out;
  }

 private:
  mutable std::mutex mutex_;
  std::deque<std::pair<std::string, std::atomic<int64_t>>> entries_;  // deque: stable addresses
};

inline void bump(std::atomic<int64_t>& counter, int64_t by = 1) {
  counter.fetch_add(by, std::memory_order_relaxed);
}

}  // namespace slam

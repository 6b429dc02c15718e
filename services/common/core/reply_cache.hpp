#pragma once
// The responder side of a request that cannot be lost (see request_retry.hpp): requesters resend a
// request under the same id until answered, so a responder sees repeats. It asks admit() first:
// a new id is executed; a repeat of an id still executing is dropped (its reply is on the way and
// every requester sees it); a repeat of an answered id gets the same reply again, not a second
// execution. Bounded: the last `capacity` ids are kept, far more than requesters retry at once.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <unordered_map>

namespace slam {

enum class Admission { Execute, Executing, Answered };

template <class Reply>
class ReplyCache {
 public:
  static constexpr std::size_t kDefaultCapacity = 1024;

  struct Verdict {
    Admission admission;
    std::optional<Reply> reply;  // when Answered: the reply to send again
  };

  explicit ReplyCache(std::size_t capacity = kDefaultCapacity) : capacity_(capacity == 0 ? 1 : capacity) {}

  // Id 0 is "no id" (a requester that does not retry): always executed, never remembered.
  Verdict admit(uint64_t id) {
    if (id == 0) return {Admission::Execute, std::nullopt};
    std::lock_guard lock(mutex_);
    auto it = entries_.find(id);
    if (it == entries_.end()) {
      remember(id, std::nullopt);
      return {Admission::Execute, std::nullopt};
    }
    if (!it->second) return {Admission::Executing, std::nullopt};
    return {Admission::Answered, it->second};
  }

  // Records the reply to `id`, so a repeat gets it; also when `id` was evicted meanwhile.
  void complete(uint64_t id, const Reply& reply) {
    if (id == 0) return;
    std::lock_guard lock(mutex_);
    auto it = entries_.find(id);
    if (it == entries_.end())
      remember(id, reply);
    else
      it->second = reply;
  }

  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
  }

 private:
  void remember(uint64_t id, std::optional<Reply> reply) {
    entries_.emplace(id, std::move(reply));
    order_.push_back(id);
    while (order_.size() > capacity_) {
      entries_.erase(order_.front());
      order_.pop_front();
    }
  }

  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::unordered_map<uint64_t, std::optional<Reply>> entries_;
  std::deque<uint64_t> order_;  // oldest first
};

}  // namespace slam

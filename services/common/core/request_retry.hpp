#pragma once
// The requester side of a request that cannot be lost: ids unique across requesters, and when to
// send the same request again. A requester resends a request with the same id until the reply with
// that id arrives or the deadline passes; the responder answers a repeat from its ReplyCache
// (reply_cache.hpp), so a copy lost before discovery or in flight costs one retry interval.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>

namespace slam {

// Request ids: a random 64-bit base per source plus a counter, so ids of different processes and
// hosts do not collide and a restarted requester never reuses an old one. Never 0 (0 means "no id").
class RequestIdSource {
 public:
  RequestIdSource();
  uint64_t next();

 private:
  uint64_t base_;
  std::atomic<uint64_t> counter_{0};
};

struct RetryPolicy {
  std::chrono::milliseconds first_interval{200};  // before the first resend
  std::chrono::milliseconds max_interval{1000};   // intervals double up to this
  std::chrono::milliseconds timeout{5000};        // no reply by then: give up
};

// When to send one request: at the start, then after intervals doubling from first_interval up
// to max_interval, until the deadline.
class RetrySchedule {
 public:
  using Clock = std::chrono::steady_clock;

  RetrySchedule(const RetryPolicy& policy, Clock::time_point start)
      : next_(start),
        interval_(policy.first_interval),
        max_interval_(policy.max_interval),
        deadline_(start + policy.timeout) {}

  // True when a copy is due at `now` (and not past the deadline); the schedule then moves to the
  // next send time, so each due time answers true once.
  bool due(Clock::time_point now) {
    if (expired(now) || now < next_) return false;
    next_ = now + interval_;
    interval_ = std::min(interval_ * 2, max_interval_);
    return true;
  }
  bool expired(Clock::time_point now) const { return now >= deadline_; }
  Clock::time_point next_send() const { return std::min(next_, deadline_); }
  Clock::time_point deadline() const { return deadline_; }

 private:
  Clock::time_point next_;
  std::chrono::milliseconds interval_;
  std::chrono::milliseconds max_interval_;
  Clock::time_point deadline_;
};

}  // namespace slam

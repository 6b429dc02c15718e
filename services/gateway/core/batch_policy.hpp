#pragma once
// When the gateway's batch of observations goes out: before an observation that would take it
// over its limits (observations or points, so a batch stays within one UDP datagram; one message
// larger than that goes in a batch of its own), as soon as it is full, or once its oldest
// observation has waited the longest the operator allows (--batch-ms). Plain bookkeeping; the node
// keeps the samples.
#include <cstddef>
#include <cstdint>

namespace slam::gateway {

struct BatchLimits {
  std::size_t max_observations = 128;
  std::size_t max_points = 3000;  // 16 bytes each: with the observations' headers under 64 KB
  std::int64_t max_wait_ns = 10'000'000;
};

class BatchPolicy {
 public:
  explicit BatchPolicy(BatchLimits limits) : limits_(limits) {}

  // Whether an observation with `points` points still goes into this batch (always into an empty
  // one); if not, the batch is written first.
  bool fits(std::size_t points) const;
  // Counts one more observation with `points` points, added at `now_mono_ns`. True when the batch
  // is full and must be written now.
  bool add(std::size_t points, std::int64_t now_mono_ns);
  bool empty() const { return observations_ == 0; }
  // When the oldest observation must have left (monotonic); only meaningful when not empty().
  std::int64_t due_ns() const { return first_ns_ + limits_.max_wait_ns; }
  bool due(std::int64_t now_mono_ns) const { return !empty() && now_mono_ns >= due_ns(); }
  // What still goes in before the batch is full: observations, and points (either one fills it).
  std::size_t observations_left() const {
    return limits_.max_observations > observations_ ? limits_.max_observations - observations_ : 0;
  }
  std::size_t points_left() const { return limits_.max_points > points_ ? limits_.max_points - points_ : 0; }
  // The batch was written: the next observation starts a new one.
  void written();

 private:
  BatchLimits limits_;
  std::size_t observations_ = 0;
  std::size_t points_ = 0;
  std::int64_t first_ns_ = 0;
};

}  // namespace slam::gateway

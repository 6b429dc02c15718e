#pragma once
// Delays between reconnection attempts: initial, then doubling up to a ceiling, back to initial
// after a success. A broker that restarts is found again within a second; one that stays down is
// not hammered.
#include <chrono>
#include <cstdint>

namespace slam::mqtt {

class Backoff {
 public:
  Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds ceiling);

  // The delay before the next attempt; each call doubles the following one, up to the ceiling.
  std::chrono::milliseconds next();
  // After a successful connection.
  void reset();
  // Attempts since the last reset (0 before the first failure).
  std::uint32_t failures() const { return failures_; }

 private:
  std::chrono::milliseconds initial_;
  std::chrono::milliseconds ceiling_;
  std::chrono::milliseconds current_;
  std::uint32_t failures_ = 0;
};

}  // namespace slam::mqtt

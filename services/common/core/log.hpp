#pragma once
// Logging: one spdlog logger per process, lines prefixed with the service name, and a
// rate limiter so a flood of bad input cannot flood the log.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>

namespace slam {

// Sets up the default logger: "2026-11-22 10:00:00.123 [gateway] [info] text" on stderr.
// Returns false (and keeps "info") when `level` is not a spdlog level name.
bool setup_logging(std::string_view service, std::string_view level);

// Allows one log line per key per interval and counts the suppressed ones, so the next line
// can say how many were dropped. Thread-safe.
class RateLimiter {
 public:
  explicit RateLimiter(std::chrono::milliseconds interval = std::chrono::seconds(1)) : interval_(interval) {}

  // Returns true when a line for `key` may be written now; `*suppressed` gets the number of
  // lines dropped for that key since the last one written.
  bool allow(const std::string& key, uint64_t* suppressed);

 private:
  struct Slot {
    std::chrono::steady_clock::time_point last{};
    uint64_t suppressed = 0;
  };
  static constexpr size_t kMaxKeys = 4096;
  std::chrono::milliseconds interval_;
  std::mutex mutex_;
  std::unordered_map<std::string, Slot> slots_;
};

}  // namespace slam

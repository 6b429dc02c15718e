#pragma once
// Logging: one spdlog logger per process, lines prefixed with the service name, and a
// rate limiter so a flood of bad input cannot flood the log.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
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
  // lines dropped for that key since the last one written. `now` is a parameter for tests.
  bool allow(const std::string& key, uint64_t* suppressed,
             std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

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

// The one way to write a warning that a flood could repeat (bad input, failed writes): at most
// one line per key per interval, and the first line after a quiet spell ends with
// " (N similar suppressed)" when N lines of that key were dropped. Thread-safe.
//   RateLimitedLog log_;                                   // a member, one per component
//   log_.warn("bad_length:" + robot, "robot '{}': bad length {}", robot, n);
// Keys are per cause (reason, robot, topic); keep them bounded in kind, not only in number.
class RateLimitedLog {
 public:
  explicit RateLimitedLog(std::chrono::milliseconds interval = std::chrono::seconds(1))
      : limiter_(interval) {}

  // Writes the formatted warning unless `key` had a line within the interval; true when written.
  template <typename... Args>
  bool warn(const std::string& key, spdlog::format_string_t<Args...> format, Args&&... args) {
    const std::optional<std::string> tail = admit(key);
    if (!tail) return false;
    spdlog::warn("{}{}", fmt::format(format, std::forward<Args>(args)...), *tail);
    return true;
  }

  // For a line that has a further condition of its own (e.g. a budget over all keys): std::nullopt
  // when `key` is suppressed now, else the tail to append to the line ("" or " (N similar suppressed)").
  std::optional<std::string> admit(
      const std::string& key, std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

 private:
  RateLimiter limiter_;
};

}  // namespace slam

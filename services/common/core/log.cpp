#include "common/core/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace slam {

bool setup_logging(std::string_view service, std::string_view level) {
  spdlog::drop(std::string(service));  // set up again (tests, reconfiguration): replace, do not throw
  auto logger = spdlog::stderr_color_mt(std::string(service));
  logger->set_pattern("%Y-%m-%d %H:%M:%S.%e [%n] [%l] %v");
  spdlog::set_default_logger(logger);
  const auto parsed = spdlog::level::from_str(std::string(level));
  // from_str maps unknown names to "off"; only accept "off" when asked for.
  if (parsed == spdlog::level::off && level != "off") {
    spdlog::set_level(spdlog::level::info);
    return false;
  }
  spdlog::set_level(parsed);
  spdlog::flush_on(spdlog::level::info);
  return true;
}

bool RateLimiter::allow(const std::string& key, uint64_t* suppressed,
                        std::chrono::steady_clock::time_point now) {
  std::lock_guard lock(mutex_);
  // Keys may come from untrusted input (robot ids): bound the table instead of growing forever.
  if (slots_.size() >= kMaxKeys && !slots_.contains(key)) slots_.clear();
  Slot& slot = slots_[key];
  if (slot.last != std::chrono::steady_clock::time_point{} && now - slot.last < interval_) {
    ++slot.suppressed;
    return false;
  }
  if (suppressed) *suppressed = slot.suppressed;
  slot.suppressed = 0;
  slot.last = now;
  return true;
}

std::optional<std::string> RateLimitedLog::admit(const std::string& key,
                                                 std::chrono::steady_clock::time_point now) {
  uint64_t suppressed = 0;
  if (!limiter_.allow(key, &suppressed, now)) return std::nullopt;
  if (suppressed == 0) return std::string();
  return " (" + std::to_string(suppressed) + " similar suppressed)";
}

}  // namespace slam

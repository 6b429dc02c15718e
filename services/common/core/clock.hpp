#pragma once
// Wall-clock and monotonic time in the units the IDL uses.
#include <chrono>
#include <cstdint>

namespace slam {

// Unix epoch nanoseconds, as in every *_ns IDL field.
inline int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

inline int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace slam

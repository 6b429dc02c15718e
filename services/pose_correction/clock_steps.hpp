#pragma once
// A caller's clock made safe to measure ages and intervals by. A wall clock set back (by hand, by
// NTP after a long drift) or a log whose stamps restart would otherwise make every keyframe made
// before look younger than the ones after for hours: none of them old map to tie to, no silent
// robot's keyframe stale, no optimisation due. Each step back larger than the tolerance is taken
// out (the clock carries on from the latest time it gave); smaller ones (jitter, messages that
// queued) pass unchanged, and so do steps forward, which only make earlier things look older.
// Plain data, deterministic.
#include <cstdint>
#include <limits>

namespace slam::correction {

class ClockSteps {
 public:
  explicit ClockSteps(int64_t tolerance_ns) : tolerance_ns_(tolerance_ns) {}

  // `t_ns` on the caller's clock, on the clock with its steps back taken out.
  int64_t operator()(int64_t t_ns) {
    int64_t t = 0;
    if (__builtin_add_overflow(t_ns, offset_ns_, &t)) t = kMax;  // the offset is never negative
    if (latest_ns_ != kMin && t < latest_ns_) {
      const uint64_t back = static_cast<uint64_t>(latest_ns_) - static_cast<uint64_t>(t);  // no overflow
      if (back > static_cast<uint64_t>(tolerance_ns_)) {
        const auto room = static_cast<uint64_t>(kMax - offset_ns_);
        offset_ns_ = back > room ? kMax : offset_ns_ + static_cast<int64_t>(back);
        t = latest_ns_;
        ++steps_;
      }
    }
    if (t > latest_ns_) latest_ns_ = t;
    return t;
  }
  // How many steps back were taken out, and how much time they added up to.
  int64_t steps() const { return steps_; }
  int64_t offset_ns() const { return offset_ns_; }

 private:
  static constexpr int64_t kMin = std::numeric_limits<int64_t>::min();
  static constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
  int64_t tolerance_ns_;
  int64_t offset_ns_ = 0;
  int64_t latest_ns_ = kMin;
  int64_t steps_ = 0;
};

}  // namespace slam::correction

#pragma once
// Messages per second for the Main tab: counts events, and once a second turns the count into
// a rate kept in a short ring for ImGui's small plots.
#include <array>
#include <cstddef>
#include <cstdint>

namespace slam::viewer {

class RateMeter {
 public:
  static constexpr size_t kHistory = 60;  // seconds shown in the plot

  void add(uint64_t n = 1) {
    pending_ += n;
    total_ += n;
  }
  // Call every frame with a monotonic clock; closes whole seconds that have passed.
  void tick(int64_t now_ns);

  uint64_t total() const { return total_; }
  float latest() const { return filled_ ? history_[(head_ + kHistory - 1) % kHistory] : 0.0f; }
  // Oldest first, `count()` values, for PlotLines with values_offset = offset().
  const float* history() const { return history_.data(); }
  int offset() const { return static_cast<int>(head_); }
  int count() const { return static_cast<int>(kHistory); }

 private:
  std::array<float, kHistory> history_{};
  size_t head_ = 0;  // next slot to write
  bool filled_ = false;
  uint64_t pending_ = 0;
  uint64_t total_ = 0;
  int64_t window_start_ns_ = -1;
};

}  // namespace slam::viewer

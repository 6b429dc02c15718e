// Per-second rate history (see rate_meter.hpp).
#include "viewer/core/rate_meter.hpp"

namespace slam::viewer {

void RateMeter::tick(int64_t now_ns) {
  constexpr int64_t kSecond = 1'000'000'000;
  if (window_start_ns_ < 0) {
    window_start_ns_ = now_ns;
    return;
  }
  while (now_ns - window_start_ns_ >= kSecond) {
    history_[head_] = static_cast<float>(pending_);
    head_ = (head_ + 1) % kHistory;
    filled_ = true;
    pending_ = 0;
    window_start_ns_ += kSecond;
  }
}

}  // namespace slam::viewer

// Backoff: exponential with a ceiling.
#include "common/mqtt/backoff.hpp"

#include <algorithm>

namespace slam::mqtt {

Backoff::Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds ceiling)
    : initial_(std::max(initial, std::chrono::milliseconds(1))),
      ceiling_(std::max(ceiling, initial_)),
      current_(initial_) {}

std::chrono::milliseconds Backoff::next() {
  const auto delay = current_;
  current_ = current_ >= ceiling_ / 2 ? ceiling_ : current_ * 2;
  ++failures_;
  return delay;
}

void Backoff::reset() {
  current_ = initial_;
  failures_ = 0;
}

}  // namespace slam::mqtt

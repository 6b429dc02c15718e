#include "common/core/request_retry.hpp"

#include <random>

namespace slam {

RequestIdSource::RequestIdSource() {
  std::random_device random;
  base_ = (static_cast<uint64_t>(random()) << 32) ^ static_cast<uint64_t>(random());
}

uint64_t RequestIdSource::next() {
  uint64_t id = base_ + counter_.fetch_add(1, std::memory_order_relaxed) + 1;
  while (id == 0) id = base_ + counter_.fetch_add(1, std::memory_order_relaxed) + 1;
  return id;
}

}  // namespace slam

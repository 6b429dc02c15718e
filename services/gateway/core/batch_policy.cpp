#include "gateway/core/batch_policy.hpp"

namespace slam::gateway {

bool BatchPolicy::fits(std::size_t points) const {
  return observations_ == 0 ||
         (observations_ < limits_.max_observations && points_ + points <= limits_.max_points);
}

bool BatchPolicy::add(std::size_t points, std::int64_t now_mono_ns) {
  if (observations_ == 0) first_ns_ = now_mono_ns;
  ++observations_;
  points_ += points;
  return observations_ >= limits_.max_observations || points_ >= limits_.max_points;
}

void BatchPolicy::written() {
  observations_ = 0;
  points_ = 0;
}

}  // namespace slam::gateway

// Fuzz target for the truth log parser (eval_replay's input): any bytes give samples or an error,
// never a crash; parsed samples are finite and in stamp order.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "eval/truth_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto samples = slam::bench::parse_truth_log(text);
  if (!samples) return 0;
  for (size_t i = 0; i < samples->size(); ++i) {
    const auto& s = (*samples)[i];
    if (!std::isfinite(s.truth.true_pose.x + s.truth.reported_pose.theta)) __builtin_trap();
    if (i > 0 && s.stamp_ns < (*samples)[i - 1].stamp_ns) __builtin_trap();
  }
  return 0;
}

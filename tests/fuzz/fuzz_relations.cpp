// Fuzz target for the benchmark relation parser (eval_log's reference): any line gives a relation or
// an error, never a crash; a parsed relation is finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "eval/relation_metric.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto relation = slam::bench::parse_relation(text);
  if (!relation) return 0;
  if (!std::isfinite(relation->t1 + relation->t2 + relation->motion.x + relation->motion.y +
                     relation->motion.theta))
    __builtin_trap();
  return 0;
}

// Fuzz target for the Java world text parser: any bytes give a world or an error, never a crash;
// a parsed world must also answer ray and clearance queries.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "simulator/core/world_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto world = slam::sim::parse_java_world(text, "fuzz");
  if (!world) return 0;
  const slam::sim::Bounds& b = world->bounds();
  const slam::Vec2 centre{(b.min.x + b.max.x) / 2, (b.min.y + b.max.y) / 2};
  const double range = world->cast(centre, {0.6, 0.8}, 1e3);
  if (!(range >= 0.0 && range <= 1e3)) __builtin_trap();
  (void)world->is_free(centre, 0.1);
  return 0;
}

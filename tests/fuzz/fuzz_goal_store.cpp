// Fuzz target for the planner's goal file: any bytes give a record or an error, never a crash; a
// parsed record formats to text that parses back to the same goals.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "planner/core/goal_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto record = slam::planner::parse_goal_record(text);
  if (!record) return 0;
  auto again = slam::planner::parse_goal_record(slam::planner::format_goal_record(*record));
  if (!again || again->goals.size() != record->goals.size() || again->homes.size() != record->homes.size())
    __builtin_trap();
  (void)slam::planner::goals_to_resume(*record);
  return 0;
}

#pragma once
// Worlds that need no file, by name: "empty", "office", "maze", "track" and "rooms".
#include <span>
#include <string_view>

#include "common/core/result.hpp"
#include "simulator/core/world.hpp"

namespace slam::sim {

// The names builtin_world() accepts.
std::span<const std::string_view> builtin_world_names();

// "empty":  10 x 10 m, border walls only.
// "office": 20 x 15 m floor, a 3 m corridor along x with four rooms on each side, 1 m doors, and a
//           few boxes (tables, a pillar) inside rooms.
// "maze":   12 x 12 m perfect maze of 1.2 m cells (fixed layout, the same on every machine).
// "track":  6 x 6 m with the circular test track of the 2019 thesis (ch. 10.3): a 1 m wide ring
//           corridor between circles of 1.5 m and 2.5 m radius, each drawn with 64 segments.
// "rooms":  12 x 8 m, four identical 3 x 6 m rooms (same 1 m door, table and shelf) in a row above a
//           2 m corridor: a world built to tempt a wrong loop closure.
Result<World> builtin_world(std::string_view name);

}  // namespace slam::sim

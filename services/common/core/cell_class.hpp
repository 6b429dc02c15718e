#pragma once
// The cell class octet of GridSnapshot.cells / GridTiles.data (map.idl CELL_*), for the cores that
// must not include generated DDS headers (mapper, planner, viewer). One definition for all of them.
#include <cstdint>

namespace slam {

inline constexpr uint8_t kCellUnknown = 0;
inline constexpr uint8_t kCellFree = 1;
inline constexpr uint8_t kCellOccupied = 2;
inline constexpr uint8_t kCellStateMask = 3;   // low two bits: the observed state
inline constexpr uint8_t kCellInflated = 4;    // within robot radius of an occupied cell
inline constexpr uint8_t kCellObstructed = 8;  // obstructed by hand by the operator

// A wall: observed occupied, or obstructed by the operator (what the inflation grows from and what
// a scan's points can lie on).
inline constexpr bool is_wall(uint8_t cell_class) {
  return (cell_class & kCellStateMask) == kCellOccupied || (cell_class & kCellObstructed) != 0;
}

}  // namespace slam

#pragma once
// The grid's configuration: one plain struct with defaults and a validator that names the bad key.
// It is what GridConfig requests (map.idl) set, what the store persists, and what rebuilds use.
#include <cstdint>

#include "common/core/result.hpp"

namespace slam::mapper {

// Log-odds are stored as int16 in units of 1/100 (a value of 85 means log-odds 0.85).
//
// Why the defaults cannot let one robot passing by erase what several robots saw:
//  * each observation updates a cell at most once (hits first, then misses skip marked cells), so a
//    scan of 360 beams converging near the robot is one miss per cell, not hundreds;
//  * occupied evidence saturates high (clamp_max 500) while a miss is small (-40) and free evidence
//    saturates low (clamp_min -200): a wall several robots confirmed sits at +500 and needs
//    (500 - 60) / 40 = 11 consecutive observations that see through it, with no hit in between,
//    before it stops being occupied; a single passing scan, or a few, only dents it;
//  * the asymmetric clamps keep free space cheap to re-occupy: from -200 three hits (+90 each, -200 ->
//    -110 -> -20 -> +70) make a cell occupied again, so new obstacles appear quickly.
struct LogOddsConfig {
  int16_t hit = 90;                 // added to the end cell of a ray (p = 0.71)
  int16_t miss = -40;               // added to cells a ray crosses (p = 0.40)
  int16_t clamp_min = -200;         // free evidence saturates here (p = 0.12)
  int16_t clamp_max = 500;          // occupied evidence saturates here (p = 0.993)
  int16_t occupied_threshold = 60;  // >= this: CELL_OCCUPIED
  int16_t free_threshold = -30;     // <= this: CELL_FREE; in between: CELL_UNKNOWN
  int16_t prior_occupied = 250;     // value an imported map's occupied pixel sets
  int16_t prior_free = -100;        // value an imported map's free pixel sets
};

// Hard limits independent of configuration: they bound memory (7 bytes per cell: log-odds, class, inflation
// count, stamp).
inline constexpr int32_t kMaxCellsPerSide = 16384;
inline constexpr int64_t kMaxCells = int64_t{1} << 27;
inline constexpr int32_t kMaxInflationCells = 127;  // radius in cells; keeps counts within uint16

struct GridConfig {
  double resolution = 0.05;  // metres per cell
  double origin_x = -10.0;   // lower-left corner of cell (0, 0), map frame
  double origin_y = -10.0;
  double width_m = 20.0;  // initial extent; the grid grows from here as data arrives
  double height_m = 20.0;
  double inflation_radius = 0.2;  // metres (robot radius)
  bool legacy_mode = false;       // 2019 behaviour: a point obstructs its cell, nothing is cleared
  double max_extent_m = 200.0;    // the grid never grows past this many metres per side
  double grow_chunk_m = 10.0;     // growth step, so a robot driving outwards does not regrow per message
  double max_range_m = 100.0;     // a point farther than this from the robot is corrupt input
  LogOddsConfig log_odds;
};

// Ok, or an error naming the key and the reason ("resolution: must be > 0, got -1").
Status validate(const GridConfig& config);

// Cells needed for `metres` at `resolution`, rounded up (at least 1).
int64_t cells_for(double metres, double resolution);

}  // namespace slam::mapper

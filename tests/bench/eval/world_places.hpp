#pragma once
// A built-in world seen the way the fleet evaluations need it: the places a robot can be sent to,
// and the planner's grid of the world as a mapper that had seen every wall would publish it.
#include <random>
#include <span>
#include <vector>

#include "planner/core/planning_grid.hpp"
#include "simulator/core/world.hpp"

namespace slam::bench {

// Places on a 0.2 m lattice clear of walls by `clearance` and connected to `from` (the simulator's
// odometry starts in the world frame, so these are map coordinates too).
std::vector<Vec2> reachable_places(const sim::World& world, Vec2 from, double clearance);

// A random place of `places` (not empty) at least `min_trip_m` in a straight line from `from`, or
// the last one drawn when 20 draws find none.
Vec2 pick_place(std::span<const Vec2> places, Vec2 from, double min_trip_m, std::mt19937_64& rng);

// `count` places of `places` (not empty) to patrol in order: each picked as pick_place from the one
// before, the first from `from`.
std::vector<Vec2> patrol_route(std::span<const Vec2> places, Vec2 from, size_t count, double min_trip_m,
                               std::mt19937_64& rng);

// The world as planner cells of `resolution`: a cell a wall runs through is occupied, one closer
// to a wall than `inflation` (the mapper's robot radius) is inflated, every other cell is free.
planner::PlanningGrid planning_grid_of(const sim::World& world, double resolution, double inflation);

}  // namespace slam::bench

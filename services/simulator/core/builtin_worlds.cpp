// Built-in worlds: fixed layouts for demos, tests and benchmarks, so nothing depends on files.
#include "simulator/core/builtin_worlds.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace slam::sim {
namespace {

using Walls = std::vector<Segment>;

// A wall along y = const from x0 to x1 with door gaps [from, to] (sorted, inside [x0, x1]).
void wall_x(Walls& w, double y, double x0, double x1,
            std::initializer_list<std::pair<double, double>> doors) {
  double x = x0;
  for (const auto& [from, to] : doors) {
    if (from > x) w.push_back({{x, y}, {from, y}});
    x = to;
  }
  if (x1 > x) w.push_back({{x, y}, {x1, y}});
}

// A wall along x = const from y0 to y1 with door gaps.
void wall_y(Walls& w, double x, double y0, double y1,
            std::initializer_list<std::pair<double, double>> doors) {
  double y = y0;
  for (const auto& [from, to] : doors) {
    if (from > y) w.push_back({{x, y}, {x, from}});
    y = to;
  }
  if (y1 > y) w.push_back({{x, y}, {x, y1}});
}

// Solid mask over `b` at 0.1 m: cells whose centre satisfies `inside` (furniture interiors, the
// areas off the track), so random spawns land where a robot could have driven to.
template <class Inside>
OccupancyImage solid_mask(const Bounds& b, Inside inside) {
  OccupancyImage m;
  m.resolution = 0.1;
  m.origin = b.min;
  m.width = static_cast<int>(std::ceil(b.width() / m.resolution));
  m.height = static_cast<int>(std::ceil(b.height() / m.resolution));
  m.occupied.resize(static_cast<size_t>(m.width) * static_cast<size_t>(m.height));
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      m.occupied[static_cast<size_t>(y * m.width + x)] =
          inside(Vec2{b.min.x + (x + 0.5) * m.resolution, b.min.y + (y + 0.5) * m.resolution}) ? 1 : 0;
  return m;
}

void box(Walls& w, Vec2 lo, Vec2 hi) {
  w.push_back({lo, {hi.x, lo.y}});
  w.push_back({{hi.x, lo.y}, hi});
  w.push_back({hi, {lo.x, hi.y}});
  w.push_back({{lo.x, hi.y}, lo});
}

Result<World> office() {
  Walls w;
  // Corridor between y = 6 and y = 9; rooms below split at x = 5, 10, 15, above at x = 4, 8, 14.
  wall_x(w, 6.0, 0.0, 20.0, {{2.0, 3.0}, {7.0, 8.0}, {12.0, 13.0}, {17.0, 18.0}});
  wall_x(w, 9.0, 0.0, 20.0, {{1.5, 2.5}, {5.5, 6.5}, {10.5, 11.5}, {16.5, 17.5}});
  for (double x : {5.0, 10.0, 15.0}) wall_y(w, x, 0.0, 6.0, {});
  // Rooms above: the two large ones on the right share a door so the floor has a loop.
  wall_y(w, 4.0, 9.0, 15.0, {});
  wall_y(w, 8.0, 9.0, 15.0, {});
  wall_y(w, 14.0, 9.0, 15.0, {{12.0, 13.0}});
  const std::array<Bounds, 4> furniture = {{
      {{10.5, 12.5}, {12.5, 13.5}},  // meeting table
      {{1.0, 1.0}, {2.5, 1.8}},      // desk
      {{16.0, 2.0}, {17.2, 2.8}},    // desk
      {{9.8, 7.3}, {10.2, 7.7}},     // pillar in the corridor
  }};
  for (const Bounds& f : furniture) box(w, f.min, f.max);
  const Bounds bounds{{0.0, 0.0}, {20.0, 15.0}};
  auto solid = solid_mask(bounds, [&](Vec2 p) {
    for (const Bounds& f : furniture)
      if (f.contains(p)) return true;
    return false;
  });
  return World::create("office", bounds, std::move(w), std::move(solid));
}

// Recursive-backtracker maze. std::mt19937's sequence is fixed by the standard and only `rng() % n`
// is used (distributions are implementation-defined), so the layout is identical everywhere.
Result<World> maze() {
  constexpr int kN = 10;
  constexpr double kCell = 1.2;
  std::array<bool, kN * kN> seen{};
  // open_east[c]: no wall between cell c and its east neighbour; open_north likewise.
  std::array<bool, kN * kN> open_east{}, open_north{};
  std::mt19937 rng(2019);
  std::vector<int> stack{0};
  seen[0] = true;
  while (!stack.empty()) {
    const int c = stack.back(), cx = c % kN, cy = c / kN;
    std::array<int, 4> next{};
    int n = 0;
    if (cx + 1 < kN && !seen[c + 1]) next[n++] = c + 1;
    if (cx > 0 && !seen[c - 1]) next[n++] = c - 1;
    if (cy + 1 < kN && !seen[c + kN]) next[n++] = c + kN;
    if (cy > 0 && !seen[c - kN]) next[n++] = c - kN;
    if (n == 0) {
      stack.pop_back();
      continue;
    }
    const int to = next[rng() % static_cast<uint32_t>(n)];
    if (to == c + 1) open_east[c] = true;
    if (to == c - 1) open_east[to] = true;
    if (to == c + kN) open_north[c] = true;
    if (to == c - kN) open_north[to] = true;
    seen[to] = true;
    stack.push_back(to);
  }
  Walls w;
  for (int cy = 0; cy < kN; ++cy) {
    for (int cx = 0; cx < kN; ++cx) {
      const int c = cy * kN + cx;
      const double x0 = cx * kCell, y0 = cy * kCell, x1 = x0 + kCell, y1 = y0 + kCell;
      if (cx + 1 < kN && !open_east[c]) w.push_back({{x1, y0}, {x1, y1}});
      if (cy + 1 < kN && !open_north[c]) w.push_back({{x0, y1}, {x1, y1}});
    }
  }
  return World::create("maze", {{0.0, 0.0}, {kN * kCell, kN * kCell}}, std::move(w));
}

void circle(Walls& w, Vec2 c, double r, int segments) {
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2.0 * std::numbers::pi * i / segments;
    const double a1 = 2.0 * std::numbers::pi * (i + 1) / segments;
    w.push_back(
        {{c.x + r * std::cos(a0), c.y + r * std::sin(a0)}, {c.x + r * std::cos(a1), c.y + r * std::sin(a1)}});
  }
}

Result<World> track() {
  const Vec2 centre{3.0, 3.0};
  constexpr double kInner = 1.5, kOuter = 2.5;
  Walls w;
  circle(w, centre, kOuter, 64);
  circle(w, centre, kInner, 64);
  const Bounds bounds{{0.0, 0.0}, {6.0, 6.0}};
  auto solid = solid_mask(bounds, [&](Vec2 p) {
    const double r = norm(p - centre);
    return r < kInner || r > kOuter;
  });
  return World::create("track", bounds, std::move(w), std::move(solid));
}

// Four identical rooms in a row above one corridor: each room is the previous one shifted by its
// width, door and furniture included, so a scan in one room matches every other room equally well.
Result<World> rooms() {
  constexpr int kRooms = 4;
  constexpr double kWidth = 3.0, kCorridor = 2.0, kTop = 8.0;
  constexpr double kDoorFrom = 1.0, kDoorTo = 2.0;  // along each room's corridor wall
  // Per room, relative to its bottom-left corner: a table in the middle, a shelf against the left wall.
  const std::array<Bounds, 2> furniture_in_room = {{
      {{0.9, 2.6}, {2.1, 3.4}},  // table
      {{0.0, 4.6}, {0.4, 5.6}},  // shelf
  }};
  Walls w;
  std::vector<Bounds> furniture;
  for (int k = 0; k < kRooms; ++k) {
    const double x0 = k * kWidth;
    wall_x(w, kCorridor, x0, x0 + kWidth, {{x0 + kDoorFrom, x0 + kDoorTo}});
    if (k > 0) wall_y(w, x0, kCorridor, kTop, {});
    for (const Bounds& f : furniture_in_room)
      furniture.push_back({{x0 + f.min.x, kCorridor + f.min.y}, {x0 + f.max.x, kCorridor + f.max.y}});
  }
  for (const Bounds& f : furniture) box(w, f.min, f.max);
  const Bounds bounds{{0.0, 0.0}, {kRooms * kWidth, kTop}};
  auto solid = solid_mask(bounds, [&](Vec2 p) {
    for (const Bounds& f : furniture)
      if (f.contains(p)) return true;
    return false;
  });
  return World::create("rooms", bounds, std::move(w), std::move(solid));
}

constexpr std::array<std::string_view, 5> kNames = {"empty", "office", "maze", "track", "rooms"};

}  // namespace

std::span<const std::string_view> builtin_world_names() {
  return kNames;
}

Result<World> builtin_world(std::string_view name) {
  if (name == "empty") return World::create("empty", {{0.0, 0.0}, {10.0, 10.0}}, {});
  if (name == "office") return office();
  if (name == "maze") return maze();
  if (name == "track") return track();
  if (name == "rooms") return rooms();
  return Error{fmt::format("unknown built-in world '{}' (known: {})", name, fmt::join(kNames, ", "))};
}

}  // namespace slam::sim

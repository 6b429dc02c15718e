#pragma once
// How an occupancy cell octet (state in the low 2 bits, inflated / obstructed flags above) becomes
// a colour. The GPU gets the 16-entry table from cell_palette(), so the shader and the tests use
// this one definition.
#include <array>
#include <cstdint>
#include <string>

#include "common/core/cell_class.hpp"

namespace slam::viewer {

struct Rgba {
  float r = 0.0f, g = 0.0f, b = 0.0f, a = 1.0f;
  bool operator==(const Rgba&) const = default;
};

// Operator-adjustable colours (Grid tab); local to the viewer.
struct GridColors {
  Rgba unknown{0.50f, 0.50f, 0.50f, 1.0f};
  Rgba free{0.93f, 0.93f, 0.90f, 1.0f};
  Rgba occupied{0.08f, 0.08f, 0.10f, 1.0f};
  Rgba inflated{0.95f, 0.65f, 0.20f, 1.0f};    // blended over free cells near obstacles
  Rgba obstructed{0.75f, 0.10f, 0.45f, 1.0f};  // operator obstructions win over everything
  float inflation_mix = 0.35f;                 // how much of `inflated` shows over the state colour
  float alpha = 1.0f;                          // whole-map opacity
  bool show_inflation = true;
};

// Colour of one cell octet. Unused state 3 renders like unknown.
Rgba cell_color(uint8_t cell, const GridColors& colors);

// cell_color for every value of the low 4 bits (state + flags), in that order.
std::array<Rgba, 16> cell_palette(const GridColors& colors);

// Robot colours: a fixed palette picked by a hash of the id, so a robot keeps its colour across
// restarts and in every viewer, whatever order robots are seen in.
Rgba default_robot_color(const std::string& robot_id);

}  // namespace slam::viewer

// Cell and robot colours (see cell_colors.hpp).
#include "viewer/core/cell_colors.hpp"

namespace slam::viewer {
namespace {

Rgba mix(const Rgba& a, const Rgba& b, float t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t, a.a + (b.a - a.a) * t};
}

// Distinct, saturated colours that stand out on grey, white and near-black cells.
constexpr std::array<Rgba, 10> kPalette{{{0.90f, 0.10f, 0.29f, 1.0f},
                                         {0.24f, 0.71f, 0.29f, 1.0f},
                                         {0.00f, 0.51f, 0.78f, 1.0f},
                                         {0.96f, 0.51f, 0.19f, 1.0f},
                                         {0.57f, 0.12f, 0.71f, 1.0f},
                                         {0.27f, 0.94f, 0.94f, 1.0f},
                                         {0.94f, 0.20f, 0.90f, 1.0f},
                                         {0.82f, 0.96f, 0.24f, 1.0f},
                                         {0.00f, 0.50f, 0.50f, 1.0f},
                                         {0.67f, 0.43f, 0.16f, 1.0f}}};

}  // namespace

Rgba cell_color(uint8_t cell, const GridColors& colors) {
  Rgba c;
  if (cell & kCellObstructed) {
    c = colors.obstructed;
  } else {
    switch (cell & kCellStateMask) {
      case kCellFree:
        c = colors.free;
        break;
      case kCellOccupied:
        c = colors.occupied;
        break;
      default:
        c = colors.unknown;
        break;
    }
    if ((cell & kCellInflated) && colors.show_inflation && (cell & kCellStateMask) != kCellOccupied)
      c = mix(c, colors.inflated, colors.inflation_mix);
  }
  c.a *= colors.alpha;
  return c;
}

std::array<Rgba, 16> cell_palette(const GridColors& colors) {
  std::array<Rgba, 16> out{};
  for (unsigned v = 0; v < out.size(); ++v) out[v] = cell_color(static_cast<uint8_t>(v), colors);
  return out;
}

Rgba default_robot_color(const std::string& robot_id) {
  uint32_t h = 2166136261u;  // FNV-1a
  for (unsigned char ch : robot_id) h = (h ^ ch) * 16777619u;
  return kPalette[h % kPalette.size()];
}

}  // namespace slam::viewer

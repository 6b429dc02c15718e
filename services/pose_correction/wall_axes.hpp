#pragma once
// The heading indoor walls give. Most buildings' walls run along two perpendicular directions, so
// the straight walls a keyframe saw, read in its own frame and compared with the map's axes, tell
// the keyframe's heading modulo a quarter turn. Nothing else does while a robot explores new
// ground: its matches there can only agree with its own fresh trail, which carries the heading its
// odometry drifted to. A map without such axes (a ring, walls at many angles) never gets them, and
// then no keyframe is corrected this way.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::correction {

struct WallAxisOptions {
  double thinning_cell_m = 0.05;     // the points are thinned to one per cell of this size
  double line_band_m = 0.05;         // the bands the search counts points in, across the walls
  int min_line_points = 8;           // fewer (thinned) points: no line
  double min_line_length_m = 0.6;    // shorter: no line (a table leg, a corner)
  double max_line_tilt_rad = 0.05;   // a line's fit this far off the keyframe's axes is not a wall of them
  double point_sigma_m = 0.015;      // floor of a line's spread across (sensor noise); 3x: off the line
  double max_line_spread_m = 0.025;  // spread across above this: not one straight wall, or too noisy
  double max_sigma_rad = 0.02;       // a reading less certain than this is not used
};

// A keyframe's wall directions: `angle` in [-pi/4, pi/4), in the frame of its points, of the walls
// modulo a quarter turn.
struct WallAxisReading {
  double angle = 0.0;
  double sigma = 0.0;  // standard deviation of `angle` (rad)
  int lines = 0;
  int points = 0;  // on those lines, one per thinning cell
};

// Angle folded into [-pi/4, pi/4): directions modulo a quarter turn.
double wrap_quarter(double angle);

// Finds the straight walls among a keyframe's points and their common direction: the direction
// (modulo a quarter turn) along whose bands the points crowd most, refined by a least-squares line
// fit of each wall. Keeps its scratch between calls (allocation-free once grown): one per thread.
class WallAxisReader {
 public:
  // Nothing when the points hold no straight wall of enough points and length along the best
  // direction, or the reading is too uncertain.
  std::optional<WallAxisReading> read(std::span<const Vec2> points, const WallAxisOptions& options);

 private:
  void thin(std::span<const Vec2> points);  // into thinned_
  static Vec2 normal(int projection, double direction);
  // Index into bins_ of a point `offset` metres along the projection's normal.
  size_t band(int projection, double offset) const;
  // Sum of squared point counts per band across walls along `direction` and across it.
  double concentration(std::span<const Vec2> points, Vec2 centre, double direction);
  // Fits the walls along `direction` and across it into lines_.
  void collect_lines(std::span<const Vec2> points, Vec2 centre, double direction);

  WallAxisOptions options_;
  size_t per_side_ = 0;        // bands on either side of the centre, per projection
  std::vector<int32_t> bins_;  // point count per band, both projections
  struct LineFit {
    double angle;   // direction of the line
    double weight;  // 1 / variance of angle
    int points;
  };
  std::vector<LineFit> lines_;
  struct Keyed {
    int64_t cx, cy;  // thinning cell
    Vec2 point;
  };
  std::vector<Keyed> keyed_;
  std::vector<Vec2> thinned_;
  std::vector<Vec2> line_points_;
};

// Directions modulo a quarter turn, averaged: each as a unit vector of four times its angle.
class QuarterTurnMean {
 public:
  void add(double angle, double weight);
  double mean() const;       // in [-pi/4, pi/4)
  double agreement() const;  // weighted mean resultant length: 1 all alike, about 0 all ways
  int count() const { return count_; }

 private:
  double sum_cos_ = 0.0;
  double sum_sin_ = 0.0;
  double sum_weights_ = 0.0;
  int count_ = 0;
};

// The map's wall axes. Their direction comes from the readings of keyframes whose heading in the
// map is given, not estimated: a robot's first keyframes at its trusted start, or the first ones
// after an operator's pose. Every other keyframe's heading carries its odometry's drift and its matches'
// errors, and averaging them would tilt the axes by a degree and hold every robot to the tilt.
// The anchors' weighted median keeps one bad reading (a shelf's edge taken for a wall) out.
// The readings of all placed keyframes decide whether the map has such axes at all.
class MapWallAxes {
 public:
  static constexpr int kMinReadings = 10;
  static constexpr double kMinAgreement = 0.8;
  // An anchor must see at least two walls: one short line may be a piece of furniture.
  static constexpr int kAnchorLines = 2;
  static constexpr int kAnchorPoints = 20;

  // Whether a reading is clear enough to anchor the axes.
  static bool anchors(const WallAxisReading& reading) {
    return reading.lines >= kAnchorLines && reading.points >= kAnchorPoints;
  }
  // A reading (its angle plus the keyframe's heading in the map) at a given heading, weighed by the
  // inverse of its variance.
  void anchor(double axis_in_map, double weight);
  // A reading at a placed keyframe's estimated heading.
  void learn(double axis_in_map);
  // The axes' direction in [-pi/4, pi/4): nothing before an anchor and enough readings, or while
  // either disagree among themselves (walls at many angles, robots whose starts disagree).
  std::optional<double> axis() const;
  int readings() const { return readings_.count(); }

 private:
  struct Anchor {
    double angle;
    double weight;
  };
  std::vector<Anchor> anchors_;  // sorted by angle, unwrapped around their mean
  QuarterTurnMean anchor_mean_;
  double anchor_median_ = 0.0;
  QuarterTurnMean readings_;
};

// The keyframe heading a reading gives against the map's axes: the one modulo a quarter turn
// nearest `heading`, as the signed correction to add to it (within +-pi/4).
double heading_correction(double map_axis, const WallAxisReading& reading, double heading);

}  // namespace slam::correction

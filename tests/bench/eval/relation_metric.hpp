#pragma once
// The relation metric of the SLAM benchmark literature (Kümmerle et al., "On measuring the accuracy of
// SLAM algorithms", Autonomous Robots 27(4), 2009): a reference gives relative motions between pairs of
// stamps; each relation's error is e = d*^-1 (+) (x1^-1 (+) x2), with d* the reference motion and x1, x2
// the estimate's poses at the two stamps. Independent of where the estimate's map frame lies, so it
// scores robots whose odometry starts anywhere. Plain C++.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::bench {

// One reference relation: the motion from the pose at stamp t1 to the pose at t2, in the frame at t1.
struct Relation {
  double t1 = 0.0, t2 = 0.0;  // seconds, the log's scan stamps
  Pose motion;
};

// Reads a relation file: one relation per line, "t1 t2 x y z roll pitch yaw" (z, roll and pitch are
// ignored; 2-D benchmarks write 0). Blank lines and '#' comments are skipped; a malformed line is an
// error naming its line number.
Result<std::vector<Relation>> read_relations(const std::filesystem::path& path);
Result<Relation> parse_relation(std::string_view line);

// Mean and standard deviation of a set of values (population std, as the benchmark's tables).
struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

// The paper's table entries: absolute and squared errors, translational (m, m^2) and rotational
// (degrees, degrees^2), over the relations both stamps of which the estimate has.
struct RelationScore {
  size_t relations = 0;  // scored
  size_t missing = 0;    // a stamp the estimate has no pose for
  MeanStd trans_abs, trans_sq, rot_abs, rot_sq;
};

// Looks up poses by stamp: the estimate's pose at a stamp within tolerance of `stamp`, if any.
class StampedPoses {
 public:
  // Poses and stamps in any order (stamps may step back: the lookup takes the nearest).
  StampedPoses(std::span<const double> stamps, std::span<const Pose> poses, double tolerance_s = 1e-3);
  std::optional<Pose> at(double stamp) const;

 private:
  struct Entry {
    double stamp;
    Pose pose;
  };
  std::vector<Entry> entries_;  // sorted by stamp
  double tolerance_s_;
};

// Scores `estimate` against `relations`; relations whose duration (t2 - t1) lies outside
// [min_duration_s, max_duration_s] are left out (all by default).
RelationScore score_relations(std::span<const Relation> relations, const StampedPoses& estimate,
                              double min_duration_s = 0.0, double max_duration_s = 1e300);

// "0.031 ± 0.026 m, 1.3 ± 4.7°": the absolute errors, as the paper's tables print them.
std::string describe(const RelationScore& score);

}  // namespace slam::bench

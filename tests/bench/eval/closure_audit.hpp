#pragma once
// Loop closures judged against the ground truth. The mapper publishes each robot's correction
// map <- odom; a change whose source is a loop closure (and the optimisation after it) should move
// the robot's corrected pose towards the truth. Each change is scored at the robot's latest truth
// sample: the corrected pose's error before (old correction) and after (new correction) the change.
// A loop change that makes the error clearly larger is a false closure: worse than none (issue 13).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::bench {

// One change of a robot's correction, with the robot's latest truth sample when it was heard.
struct CorrectionChange {
  std::string robot_id;
  uint64_t version = 0;          // of the new correction
  int64_t truth_stamp_ns = 0;    // of the truth sample it is scored at
  bool loop = false;             // set by a loop closure / pose-graph optimisation (CORRECTION_LOOP)
  Pose before;                   // map <- odom until this change
  Pose after;                    // map <- odom from this change on
  Pose reported_pose;            // the robot's odometry (its own frame)
  Vec2 true_position;            // where it truly was at that instant (world frame)
  uint64_t versions_missed = 0;  // correction versions between the previous one heard and this one
};

// The error before and after one change, in metres: |world_from_map(correction ∘ odometry) - truth|.
struct ChangeErrors {
  double before_m = 0.0;
  double after_m = 0.0;
  double jump_m = 0.0;  // how far the change moved the corrected pose
};
ChangeErrors change_errors(const CorrectionChange& change, const Pose& world_from_map);

// A loop change found false, to find it again in the mapper's log (version, time).
struct FalseClosure {
  std::string robot_id;
  uint64_t version = 0;
  int64_t truth_stamp_ns = 0;
  ChangeErrors errors;
};

struct ClosureAudit {
  size_t corrections = 0;       // changes scored, any source
  size_t loop_corrections = 0;  // of which set by a loop closure
  size_t false_closures = 0;    // loop changes that increased the error by more than the threshold
  // Largest error increase (negative: every loop change reduced it) over loop changes, if any.
  std::optional<double> worst_increase_m;
  // Other changes (matches, operator) that increased the error as much: a wrong scan match.
  size_t false_matches = 0;
  double largest_jump_m = 0.0;                   // largest move of a corrected pose by one change, any source
  double largest_loop_jump_m = 0.0;              // the same over loop changes
  uint64_t versions_missed = 0;                  // changes not heard (keep-last-1 reader): scored merged
  std::vector<FalseClosure> false_closure_list;  // in the order heard
};

// Scores every change. `world_from_map`: identity for world-frame runs, else the run's alignment.
ClosureAudit audit_corrections(std::span<const CorrectionChange> changes, const Pose& world_from_map,
                               double false_closure_increase_m);

}  // namespace slam::bench

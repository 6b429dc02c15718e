#pragma once
// Ground truth as the SLAM benchmark gives it (Kümmerle et al. 2009; the Freiburg .relations files):
// relations "t1 t2 x y z roll pitch yaw", each the true motion from the robot's pose at scan stamp t1
// to its pose at t2, in the frame of the pose at t1. Picked as the benchmark's are: between scans
// about a second apart all along the trajectory, plus some between scans tens of seconds apart,
// which show how far an estimate bends over a longer stretch. Plain C++.
#include <span>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::sim {

// The robot's true pose at one of its scans.
struct TruthSample {
  double stamp_s = 0;
  Pose pose;
};

struct RelationPlan {
  double step_s = 1.0;         // short relations join consecutive anchor scans at least this far apart
  double long_span_s = 30.0;   // long relations span at least this
  double long_every_s = 10.0;  // from an anchor scan this often

  Status validate() const;
};

struct TruthRelation {
  double t1_s = 0;
  double t2_s = 0;
  Pose motion;  // pose(t1)^-1 (+) pose(t2)
};

// The relations of one robot's scans, given in stamp order. Anchors are the first scan and each
// next one at least step_s after the anchor before; short relations join consecutive anchors, and
// from an anchor every long_every_s a long one reaches the first anchor long_span_s or more ahead.
std::vector<TruthRelation> pick_relations(std::span<const TruthSample> track, const RelationPlan& plan);

// Appends "t1 t2 x y 0 0 0 yaw\n", the stamps as carmen_writer.hpp's stamp_text writes them.
void append_relation_line(const TruthRelation& relation, std::string& out);

}  // namespace slam::sim

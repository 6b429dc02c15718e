#pragma once
// The last step of a scan match: a least-squares refinement (Ceres) of a candidate pose on the
// bicubic-interpolated likelihood field, so the pose is not bound to the search lattice's cells.
#include <span>

#include "common/core/geometry.hpp"
#include "pose_correction/likelihood_field.hpp"

namespace slam::correction {

struct FieldRefinement {
  Pose pose;                 // where the refinement ended
  double score = 0.0;        // mean likelihood of the points there, 0..1
  double start_score = 0.0;  // the same at the start pose
  bool converged = false;    // Ceres returned a usable, finite solution
};

// Mean likelihood (0..1) of `points` (in the keyframe's frame) at `pose`, interpolated as the
// refinement sees the field.
double mean_likelihood(const LikelihoodField& field, const GridGeometry& geometry,
                       std::span<const Vec2> points, const Pose& pose);

// Minimises the sum of (1 - likelihood)^2 over the points, from `start`, in at most `iterations`.
FieldRefinement refine_on_field(const LikelihoodField& field, const GridGeometry& geometry,
                                std::span<const Vec2> points, const Pose& start, int iterations);

}  // namespace slam::correction

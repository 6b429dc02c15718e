#include "pose_correction/field_refinement.hpp"

#include <ceres/ceres.h>
#include <ceres/cubic_interpolation.h>

#include <algorithm>

namespace slam::correction {
namespace {

using FieldGrid = ceres::Grid2D<float, 1>;
using FieldInterpolator = ceres::BiCubicInterpolator<FieldGrid>;

// Continuous field coordinates of map point (x, y): sample (row, col) is the centre of field cell
// (box.x0 + col, box.y0 + row).
struct FieldFrame {
  Vec2 origin;  // map position of the field's cell (0, 0) centre
  double inverse_resolution = 1.0;

  FieldFrame(const LikelihoodField& field, const GridGeometry& geometry)
      : origin(geometry.centre({field.box().x0, field.box().y0})),
        inverse_resolution(1.0 / geometry.resolution) {}
};

// Residuals 1 - field(pose ∘ p) for every point: zero when each point sits on an occupied cell.
struct FieldResiduals {
  std::span<const Vec2> points;
  const FieldInterpolator* field;
  FieldFrame frame;

  template <class T>
  bool operator()(const T* pose, T* residuals) const {
    using std::cos, std::sin;
    const T c = cos(pose[2]), s = sin(pose[2]);
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec2 p = points[i];
      const T col = (pose[0] + c * p.x - s * p.y - frame.origin.x) * frame.inverse_resolution;
      const T row = (pose[1] + s * p.x + c * p.y - frame.origin.y) * frame.inverse_resolution;
      T likelihood;
      field->Evaluate(row, col, &likelihood);
      residuals[i] = T(1.0) - likelihood;
    }
    return true;
  }
};

double mean_likelihood(const FieldInterpolator& field, const FieldFrame& frame, std::span<const Vec2> points,
                       const Pose& pose) {
  double sum = 0.0;
  for (const Vec2& p : points) {
    const Vec2 q = pose.transform(p);
    double likelihood = 0.0;
    field.Evaluate((q.y - frame.origin.y) * frame.inverse_resolution,
                   (q.x - frame.origin.x) * frame.inverse_resolution, &likelihood);
    sum += std::clamp(likelihood, 0.0, 1.0);
  }
  return points.empty() ? 0.0 : sum / static_cast<double>(points.size());
}

}  // namespace

double mean_likelihood(const LikelihoodField& field, const GridGeometry& geometry,
                       std::span<const Vec2> points, const Pose& pose) {
  const FieldGrid grid(field.values().data(), 0, field.height(), 0, field.width());
  const FieldInterpolator interpolator(grid);
  return mean_likelihood(interpolator, FieldFrame(field, geometry), points, pose);
}

FieldRefinement refine_on_field(const LikelihoodField& field, const GridGeometry& geometry,
                                std::span<const Vec2> points, const Pose& start, int iterations) {
  const FieldGrid grid(field.values().data(), 0, field.height(), 0, field.width());
  const FieldInterpolator interpolator(grid);
  const FieldFrame frame(field, geometry);
  double pose_params[3] = {start.x, start.y, start.theta};
  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<FieldResiduals, ceres::DYNAMIC, 3>(
          new FieldResiduals{points, &interpolator, frame}, static_cast<int>(points.size())),
      nullptr, pose_params);
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = iterations;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  FieldRefinement out;
  out.pose = Pose{pose_params[0], pose_params[1], wrap_angle(pose_params[2])};
  out.converged = summary.IsSolutionUsable() && is_finite(out.pose);
  out.start_score = mean_likelihood(interpolator, frame, points, start);
  out.score = out.converged ? mean_likelihood(interpolator, frame, points, out.pose) : 0.0;
  return out;
}

}  // namespace slam::correction

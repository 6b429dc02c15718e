#include "pose_correction/response_spread.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

namespace slam::correction {
namespace {

// Floor of the reported covariance: the search cannot resolve below its own discretisation.
constexpr double kFloorLinearCells = 0.5;
constexpr double kFloorAngularRad = 0.5 * std::numbers::pi / 180.0;
// Candidates weighing less than this relative to the best do not change the covariance. The summed
// likelihood saturates (a point far from any wall scores 0, not minus its squared distance), so the
// many poor candidates of a wide window would otherwise outweigh the peak together.
constexpr double kNegligibleWeight = 0.05;
// Share of a window-wide uniform spread above which a direction counts as flat: a Gaussian response
// whose sigma reaches half the window's half-width already spreads this much once truncated.
constexpr double kFlatShare = 0.55;

}  // namespace

ResponseSpread response_spread(const SpreadInputs& in) {
  const SearchLattice& lattice = *in.lattice;
  // Worked in metres, heading counted as the arc it swings at the points' RMS range, so a flat
  // direction mixing position and heading (a ring) is found as one eigenvector.
  const Eigen::Vector3d scale(1.0, 1.0, in.rms_range);
  const double best_sum = in.sums[in.best];
  const Eigen::Vector3d best_scaled = lattice.offset(in.best).cwiseProduct(scale);
  double weight_sum = 0.0, distinct_sum = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  const double min_sum = best_sum + in.temperature * std::log(kNegligibleWeight);
  for (size_t index = 0; index < in.sums.size(); ++index) {
    const Eigen::Vector3d v = lattice.offset(index).cwiseProduct(scale);
    if ((v - best_scaled).norm() >= in.distinct_separation_m)
      distinct_sum = std::max(distinct_sum, static_cast<double>(in.sums[index]));
    if (in.sums[index] < min_sum) continue;
    const double w = std::exp((in.sums[index] - best_sum) / in.temperature);
    weight_sum += w;
    first += w * v;
    second += w * v * v.transpose();
  }
  const Eigen::Vector3d mean = first / weight_sum;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(second / weight_sum - mean * mean.transpose());
  // A direction whose spread comes near that of a response flat over the whole window (uniform: a
  // third of the squared half-width along it) is not pinned by the map: the window bounded it. Its
  // variance is the window's own, so tracking takes the best candidate there only weakly.
  const Eigen::Vector3d half_width(lattice.linear_steps * lattice.step_m,
                                   lattice.linear_steps * lattice.step_m,
                                   in.rms_range * lattice.angular_steps * lattice.angular_step);
  Eigen::Vector3d variances = spread.eigenvalues().cwiseMax(0.0);
  ResponseSpread out;
  for (int k = 0; k < 3; ++k) {
    const double window_variance = spread.eigenvectors().col(k).cwiseProduct(half_width).squaredNorm() / 3.0;
    if (window_variance > 0.0 && variances[k] >= kFlatShare * window_variance) {
      variances[k] = std::max(variances[k], window_variance);
      ++out.flat_directions;
    }
  }
  const Eigen::Matrix3d unscale = scale.cwiseInverse().asDiagonal();
  out.covariance =
      unscale * spread.eigenvectors() * variances.asDiagonal() * spread.eigenvectors().transpose() * unscale;
  const double floor_m = kFloorLinearCells * in.resolution;
  out.covariance.diagonal() +=
      Eigen::Vector3d(floor_m * floor_m, floor_m * floor_m, kFloorAngularRad * kFloorAngularRad);
  out.ambiguity = best_sum > 0.0 ? distinct_sum / best_sum : 0.0;
  return out;
}

}  // namespace slam::correction

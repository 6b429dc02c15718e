// OdometryTrust: exact odometry earns trust, drifting odometry loses it, and an ambiguous match
// (a corridor's flat direction) teaches nothing.
#include "pose_correction/odometry_trust.hpp"

#include <gtest/gtest.h>

#include <random>

namespace slam::correction {
namespace {

// The nominal covariance of a 0.4 m keyframe (0.021 m, 0.01 rad).
Eigen::Matrix3d nominal() {
  return Eigen::Vector3d(0.021 * 0.021, 0.021 * 0.021, 0.01 * 0.01).asDiagonal();
}

// A well-pinned match: 8 mm and a third of a degree.
Eigen::Matrix3d sharp_match() {
  return Eigen::Vector3d(0.008 * 0.008, 0.008 * 0.008, 0.006 * 0.006).asDiagonal();
}

// Keyframes whose matches differ from the odometry prediction by Gaussian noise of these sigmas.
void teach(OdometryTrust& trust, double sigma_m, double sigma_rad, const Eigen::Matrix3d& match_cov, int n) {
  std::mt19937 rng(3);
  std::normal_distribution<double> linear(0.0, sigma_m), angular(0.0, sigma_rad);
  for (int i = 0; i < n; ++i) trust.learn({linear(rng), linear(rng), angular(rng)}, match_cov, nominal());
}

TEST(OdometryTrust, ANewRobotIsTakenAtTheNominalModel) {
  const OdometryTrust trust;
  EXPECT_DOUBLE_EQ(trust.linear_scale(), 1.0);
  EXPECT_DOUBLE_EQ(trust.angular_scale(), 1.0);
  EXPECT_TRUE(trust.scaled(nominal()).isApprox(nominal()));
}

TEST(OdometryTrust, ExactOdometryIsTrustedFarAboveTheNominalModel) {
  OdometryTrust trust;
  // Only the matches' own noise (3 mm, 0.15 degrees) separates them from the odometry.
  teach(trust, 0.003, 0.0026, sharp_match(), 100);
  EXPECT_LT(trust.linear_scale(), 0.1);
  EXPECT_LT(trust.angular_scale(), 0.2);
  const Eigen::Matrix3d scaled = trust.scaled(nominal());
  EXPECT_LT(scaled(0, 0), 0.1 * nominal()(0, 0));
  EXPECT_GE(trust.linear_scale(), OdometryTrust::kMinScale);  // never taken as exact
}

TEST(OdometryTrust, StronglyDriftingOdometryIsTrustedLessThanTheNominalModel) {
  OdometryTrust trust;
  // Three times the nominal drift per keyframe: matches disagree by 6 cm and 1.7 degrees.
  teach(trust, 0.06, 0.03, sharp_match(), 100);
  EXPECT_GT(trust.linear_scale(), 4.0);
  EXPECT_GT(trust.angular_scale(), 4.0);
  EXPECT_LE(trust.linear_scale(), OdometryTrust::kMaxScale);
}

TEST(OdometryTrust, AnAmbiguousMatchTeachesNothing) {
  OdometryTrust trust;
  // A corridor: the match is free along it (a metre of sigma), so its disagreement with odometry
  // there says nothing about the odometry.
  Eigen::Matrix3d corridor = sharp_match();
  corridor(0, 0) = 1.0;
  teach(trust, 0.003, 0.0026, corridor, 100);
  EXPECT_DOUBLE_EQ(trust.linear_scale(), 1.0);
  EXPECT_EQ(trust.samples(), 0);
}

}  // namespace
}  // namespace slam::correction

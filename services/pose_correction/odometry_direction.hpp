#pragma once
// Odometry that counts a robot's travel without its sign: driven backwards, it moves forwards. Some
// wheel encoders and drivers integrate the speed's magnitude; the Freiburg 079 benchmark log is one
// (where the reference reverses at 0.5 m/s, at 183, 199 and 300-308 s, its odometry goes ahead as
// far), and each such keyframe lands its motion's length twice over off the prediction, beyond the
// tracking window. A well-pinned tracking match whose motion runs against the odometry's tells that
// the robot reverses; the keyframes after it are predicted with the odometry's translation turned
// round until a match runs with it again. Along a corridor, where no match can tell, the last
// direction seen holds. Odometry whose sign is right never shows a match against it and is left
// exactly as it is.
#include "common/core/geometry.hpp"

namespace slam::correction {

class OdometryDirection {
 public:
  // Shorter motions teach nothing: a match's noise decides their sign.
  static constexpr double kMinTravel_m = 0.05;
  // The matched motion along the odometry's direction, as a share of its length, beyond which the
  // robot drove the other way (or the same way, once reversed).
  static constexpr double kAgreement = 0.5;

  // The odometry motion between two keyframes as the robot drove it: while reversed, the same turn
  // with its translation turned round.
  Pose applied(const Pose& odom_motion) const {
    return reversed_ ? Pose{-odom_motion.x, -odom_motion.y, odom_motion.theta} : odom_motion;
  }

  // A well-pinned tracking match moved the robot by `matched_motion` (in its previous keyframe's
  // frame) where its odometry counted `odom_motion`.
  void learn(const Pose& odom_motion, const Pose& matched_motion) {
    const double length = norm(odom_motion.position());
    if (length < kMinTravel_m) return;
    const double along = dot(matched_motion.position(), odom_motion.position()) / length;
    if (along < -kAgreement * length) reversed_ = true;
    if (along > kAgreement * length) reversed_ = false;
  }

  bool reversed() const { return reversed_; }

 private:
  bool reversed_ = false;
};

}  // namespace slam::correction

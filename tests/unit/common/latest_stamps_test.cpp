// LatestStamps: the newest report wins; a forgotten robot comes back only with a newer one.
#include "common/core/latest_stamps.hpp"

#include <gtest/gtest.h>

namespace slam {
namespace {

using Verdict = LatestStamps::Verdict;

TEST(LatestStamps, OlderReportsAreStaleEqualOnesAreTaken) {
  LatestStamps stamps;
  EXPECT_EQ(stamps.judge("a", 200), Verdict::Fresh);
  EXPECT_EQ(stamps.judge("a", 150), Verdict::Stale);  // a slow state record
  EXPECT_EQ(stamps.judge("a", 200), Verdict::Fresh);  // the same message, a newer correction
  EXPECT_EQ(stamps.judge("b", 0), Verdict::Fresh);    // robots are independent
  EXPECT_EQ(stamps.judge("a", 300), Verdict::Fresh);
}

// A digest written before its gateway dropped the robot still lists it with its last stamp.
TEST(LatestStamps, AForgottenRobotComesBackOnlyWithANewerReport) {
  LatestStamps stamps;
  EXPECT_EQ(stamps.judge("a", 200), Verdict::Fresh);
  stamps.forget("a");
  EXPECT_EQ(stamps.judge("a", 200), Verdict::Forgotten);
  EXPECT_EQ(stamps.judge("a", 100), Verdict::Forgotten);
  EXPECT_EQ(stamps.judge("a", 201), Verdict::Fresh);  // it spoke again
  EXPECT_EQ(stamps.judge("a", 201), Verdict::Fresh);
}

TEST(LatestStamps, ForgettingARobotNeverHeardRefusesOnlyItsFirstStampOrOlder) {
  LatestStamps stamps;
  stamps.forget("ghost");
  EXPECT_EQ(stamps.judge("ghost", 0), Verdict::Fresh);
}

}  // namespace
}  // namespace slam

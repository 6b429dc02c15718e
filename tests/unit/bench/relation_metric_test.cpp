// The benchmark's relation metric (eval/relation_metric.hpp): parsing, pose lookup by stamp, and the
// error of each relation as the literature defines it.
#include "eval/relation_metric.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <vector>

#include "temp_dir.hpp"

namespace slam::bench {
namespace {

TEST(RelationMetric, ParsesALineAndRefusesBadOnes) {
  auto r = parse_relation(
      "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 -1.682210");
  ASSERT_TRUE(r) << r.message();
  EXPECT_DOUBLE_EQ(r->t1, 976052905.167303);
  EXPECT_DOUBLE_EQ(r->motion.y, -0.128430);
  EXPECT_DOUBLE_EQ(r->motion.theta, -1.682210);
  EXPECT_FALSE(parse_relation("1 2 3 4 5 6 7"));
  EXPECT_FALSE(parse_relation("1 2 3 4 5 6 7 x"));
  EXPECT_FALSE(parse_relation("1 2 nan 4 5 6 7 8"));
}

TEST(RelationMetric, ReadsAFileSkippingCommentsAndNamesABadLine) {
  testkit::TempDir dir("relations");
  const auto good = dir.path() / "good.relations";
  std::ofstream(good) << "# t1 t2 x y z roll pitch yaw\n\n1 2 0.5 0 0 0 0 0.1\n2 3 0.5 0 0 0 0 0\n";
  auto read = read_relations(good);
  ASSERT_TRUE(read) << read.message();
  EXPECT_EQ(read->size(), 2u);
  const auto bad = dir.path() / "bad.relations";
  std::ofstream(bad) << "1 2 0.5 0 0 0 0 0.1\n1 2 oops\n";
  auto refused = read_relations(bad);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("line 2"), std::string::npos) << refused.message();
  EXPECT_FALSE(read_relations(dir.path() / "missing.relations"));
}

TEST(RelationMetric, LooksUpPosesByStampWithinTheTolerance) {
  const std::vector<double> stamps{3.0, 1.0, 2.0};  // stamps may step back (the Intel log's do)
  const std::vector<Pose> poses{{3, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const StampedPoses lookup(stamps, poses, 1e-3);
  ASSERT_TRUE(lookup.at(2.0005));
  EXPECT_DOUBLE_EQ(lookup.at(2.0005)->x, 2.0);
  EXPECT_DOUBLE_EQ(lookup.at(0.9995)->x, 1.0);
  EXPECT_FALSE(lookup.at(2.5));
  EXPECT_FALSE(lookup.at(4.0));
}

TEST(RelationMetric, AnExactTrajectoryScoresZeroAndAFrameShiftChangesNothing) {
  // A robot driving a quarter circle; the estimate is the truth moved into another frame.
  std::vector<double> stamps;
  std::vector<Pose> truth, shifted;
  const Pose frame{120.0, -40.0, 1.0};
  for (int i = 0; i <= 20; ++i) {
    const double a = i * std::numbers::pi / 40;
    stamps.push_back(i);
    truth.push_back({5 * std::sin(a), 5 - 5 * std::cos(a), a});
    shifted.push_back(frame.compose(truth.back()));
  }
  std::vector<Relation> relations;
  for (int i = 0; i + 3 <= 20; ++i)
    relations.push_back({double(i), double(i + 3), truth[i].inverse().compose(truth[i + 3])});
  relations.push_back({0.0, 99.0, Pose{}});  // a stamp the estimate lacks
  const RelationScore s = score_relations(relations, StampedPoses(stamps, shifted));
  EXPECT_EQ(s.relations, 18u);
  EXPECT_EQ(s.missing, 1u);
  EXPECT_NEAR(s.trans_abs.mean, 0.0, 1e-9);
  EXPECT_NEAR(s.rot_abs.mean, 0.0, 1e-9);
}

TEST(RelationMetric, ErrorsAreTheRelationsDifferenceInTheFirstPosesFrame) {
  // Truth: 1 m straight ahead. Estimate: 1.1 m ahead and turned 2 degrees.
  const std::vector<double> stamps{0.0, 1.0, 10.0, 30.0};
  const double two_deg = 2 * std::numbers::pi / 180;
  const std::vector<Pose> estimate{{0, 0, 0}, {1.1, 0, two_deg}, {5, 0, 0}, {5, 0, 0}};
  const std::vector<Relation> relations{{0.0, 1.0, Pose{1.0, 0.0, 0.0}}, {10.0, 30.0, Pose{0.3, 0.4, 0.0}}};
  const StampedPoses poses(stamps, estimate);
  const RelationScore all = score_relations(relations, poses);
  EXPECT_EQ(all.relations, 2u);
  EXPECT_NEAR(all.trans_abs.mean, (0.1 + 0.5) / 2, 1e-9);
  EXPECT_NEAR(all.trans_abs.std, 0.2, 1e-9);
  EXPECT_NEAR(all.trans_sq.mean, (0.01 + 0.25) / 2, 1e-9);
  EXPECT_NEAR(all.rot_abs.mean, 1.0, 1e-9);
  const RelationScore short_only = score_relations(relations, poses, 0.0, 10.0);
  EXPECT_EQ(short_only.relations, 1u);
  EXPECT_NEAR(short_only.trans_abs.mean, 0.1, 1e-9);
  EXPECT_NE(describe(all).find("0.300 ± 0.200 m"), std::string::npos) << describe(all);
}

}  // namespace
}  // namespace slam::bench

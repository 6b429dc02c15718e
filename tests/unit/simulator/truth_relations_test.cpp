// Ground-truth relations: short ones chain consecutive anchors about a second apart, long ones span
// tens of seconds from an anchor every few seconds, each is the true motion in the first pose's frame
// (so a chain of short ones composes into the long one over the same stretch), and the lines read as
// the benchmark's eight numbers.
#include "simulator/core/truth_relations.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

// A robot driving a circle of 5 m radius at 0.5 m/s, a pose every 0.1 s of summed steps (as the
// simulation's clock adds dt), for `seconds`.
std::vector<TruthSample> circle(double seconds) {
  std::vector<TruthSample> out;
  double t = 0.05;
  for (int i = 0; t <= seconds; ++i, t += 0.1) {
    const double a = 0.1 * t;
    out.push_back({t, Pose{5 * std::sin(a), 5 - 5 * std::cos(a), wrap_angle(a)}});
  }
  return out;
}

TEST(TruthRelations, ShortRelationsChainAnchorsASecondApart) {
  const auto track = circle(20.0);
  const auto relations = pick_relations(track, RelationPlan{});
  std::vector<TruthRelation> shorts;
  for (const auto& r : relations)
    if (r.t2_s - r.t1_s < 2.0) shorts.push_back(r);
  ASSERT_EQ(shorts.size(), 19u);
  EXPECT_DOUBLE_EQ(shorts.front().t1_s, track.front().stamp_s);
  for (size_t k = 0; k < shorts.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(shorts[k].t2_s - shorts[k].t1_s, 1.0, 1e-6);
    if (k > 0) {
      EXPECT_EQ(shorts[k].t1_s, shorts[k - 1].t2_s);
    }
    // 0.5 m of arc turning 0.1 rad: nearly straight ahead in the first pose's frame.
    EXPECT_NEAR(std::hypot(shorts[k].motion.x, shorts[k].motion.y), 2 * 5 * std::sin(0.05), 1e-9);
    EXPECT_NEAR(shorts[k].motion.theta, 0.1, 1e-9);
    EXPECT_GT(shorts[k].motion.x, 0.49);
  }
}

TEST(TruthRelations, LongRelationsAreTheChainOfShortOnesComposed) {
  const auto track = circle(65.0);
  RelationPlan plan;
  plan.long_span_s = 30.0;
  plan.long_every_s = 10.0;
  const auto relations = pick_relations(track, plan);
  std::vector<TruthRelation> shorts, longs;
  for (const auto& r : relations) (r.t2_s - r.t1_s < 2.0 ? shorts : longs).push_back(r);
  // From the anchors at 0, 10, 20 and 30 s after the first scan; 40 s has no anchor 30 s ahead.
  ASSERT_EQ(longs.size(), 4u);
  for (size_t k = 0; k < longs.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(longs[k].t1_s - track.front().stamp_s, 10.0 * static_cast<double>(k), 1e-6);
    EXPECT_NEAR(longs[k].t2_s - longs[k].t1_s, 30.0, 1e-6);
    Pose chained;
    for (const auto& s : shorts)
      if (s.t1_s >= longs[k].t1_s - 1e-9 && s.t2_s <= longs[k].t2_s + 1e-9)
        chained = chained.compose(s.motion);
    EXPECT_NEAR(chained.x, longs[k].motion.x, 1e-9);
    EXPECT_NEAR(chained.y, longs[k].motion.y, 1e-9);
    EXPECT_NEAR(wrap_angle(chained.theta - longs[k].motion.theta), 0.0, 1e-9);
  }
}

TEST(TruthRelations, StampsComeFromTheTrackAndGapsAreBridged) {
  std::vector<TruthSample> track{{1.0, {}}, {1.5, {1, 0, 0}}, {2.0, {2, 0, 0}}, {9.0, {3, 0, 1}}};
  const auto relations = pick_relations(track, RelationPlan{});
  ASSERT_EQ(relations.size(), 2u);  // 1.0 -> 2.0 -> 9.0; nothing spans 30 s
  EXPECT_EQ(relations[1].t1_s, 2.0);
  EXPECT_EQ(relations[1].t2_s, 9.0);
  EXPECT_NEAR(relations[1].motion.x, 1.0, 1e-12);
  EXPECT_TRUE(pick_relations({}, RelationPlan{}).empty());
}

TEST(TruthRelations, LinesAreTheBenchmarksEightNumbers) {
  std::string line;
  append_relation_line({10.05, 11.05, Pose{0.5, -0.25, -0.1}}, line);
  EXPECT_EQ(line, "10.050000 11.050000 0.500000 -0.250000 0 0 0 -0.100000000\n");
  std::istringstream in(line);
  double v = 0;
  int fields = 0;
  while (in >> v) ++fields;
  EXPECT_EQ(fields, 8);
}

TEST(TruthRelations, PlansAreValidated) {
  EXPECT_TRUE(RelationPlan{}.validate());
  RelationPlan p;
  p.step_s = 0;
  EXPECT_THAT(p.validate().message(), HasSubstr("step_s"));
  p = RelationPlan{};
  p.long_span_s = 0.5;
  EXPECT_THAT(p.validate().message(), HasSubstr("long_span_s"));
  p = RelationPlan{};
  p.long_every_s = NAN;
  EXPECT_THAT(p.validate().message(), HasSubstr("long_every_s"));
}

}  // namespace
}  // namespace slam::sim

// The truth log's text format: what eval_mapping writes, eval_replay reads back exactly; bad lines
// are refused with their line number.
#include "eval/truth_log.hpp"

#include <gtest/gtest.h>

#include "temp_dir.hpp"

namespace slam::bench {
namespace {

TEST(TruthLogTest, WrittenSamplesReadBackToThePrintedPrecision) {
  const std::vector<TruthSample> samples = {
      {1'700'000'000'100'000'000, {"sim-1", {1.25, -2.5, 0.5}, {1.3, -2.4, 0.45}}},
      {1'700'000'000'100'000'000, {"sim-2", {0.0, 3.0, -3.1}, {0.1, 2.9, 3.1}}},
      {1'700'000'001'100'000'000, {"sim-1", {1.5, -2.5, 0.5}, {1.55, -2.4, 0.45}}}};
  testkit::TempDir dir("truth-log");
  const auto path = dir.path() / "run.truth";
  ASSERT_TRUE(write_truth_log(path, samples));
  auto read = read_truth_log(path);
  ASSERT_TRUE(read) << read.message();
  ASSERT_EQ(read->size(), samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    EXPECT_EQ((*read)[i].stamp_ns, samples[i].stamp_ns);
    EXPECT_EQ((*read)[i].truth.robot_id, samples[i].truth.robot_id);
    EXPECT_NEAR((*read)[i].truth.true_pose.y, samples[i].truth.true_pose.y, 1e-5);
    EXPECT_NEAR((*read)[i].truth.reported_pose.theta, samples[i].truth.reported_pose.theta, 1e-6);
  }
}

TEST(TruthLogTest, CommentsAndBlankLinesAreSkipped) {
  auto read = parse_truth_log("# header\n\n5 r 1 2 3 4 5 6\n");
  ASSERT_TRUE(read) << read.message();
  ASSERT_EQ(read->size(), 1U);
  EXPECT_EQ((*read)[0].truth.robot_id, "r");
  EXPECT_DOUBLE_EQ((*read)[0].truth.reported_pose.theta, 6.0);
}

TEST(TruthLogTest, BadLinesNameTheirLineAndWhatIsWrong) {
  const auto error_of = [](std::string_view text) {
    auto r = parse_truth_log(text);
    return r ? std::string("parsed") : r.message();
  };
  EXPECT_EQ(error_of("x r 1 2 3 4 5 6\n"), "truth log line 1: the stamp is not an integer");
  EXPECT_EQ(error_of("# c\n5\n"), "truth log line 2: no robot id");
  EXPECT_EQ(error_of("5 r 1 2 3 4 5\n"), "truth log line 1: expected 6 finite numbers after the robot id");
  EXPECT_EQ(error_of("5 r 1 2 nan 4 5 6\n"),
            "truth log line 1: expected 6 finite numbers after the robot id");
  EXPECT_EQ(error_of("5 r 1 2 3 4 5 6 7\n"), "truth log line 1: more than 8 fields");
  EXPECT_EQ(error_of("5 r 1 2 3 4 5 6\n4 r 1 2 3 4 5 6\n"), "truth log line 2: the stamp goes back");
}

TEST(TruthLogTest, AMissingFileIsNamed) {
  auto read = read_truth_log("/nonexistent/run.truth");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.message(), "cannot read /nonexistent/run.truth");
}

}  // namespace
}  // namespace slam::bench

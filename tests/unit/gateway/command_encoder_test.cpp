// CommandEncoder: exact v1 bytes, v2 JSON, and errors instead of wrapped values. Frame conversion
// of commands is covered in frame_correction_test.cpp.
#include "gateway/core/command_encoder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace slam::gateway {
namespace {

const Pose kIdentity{};  // a robot whose odometry frame is the map frame

TEST(CommandEncoder, V1IsExactlyFourLittleEndianBytesOnTheCmdTopic) {
  CommandEncoder encoder{protocol::CodecLimits{}};
  CommandMessages out;
  ASSERT_TRUE(encoder.encode("r1", Protocol::V1, 7, kIdentity, {1.0, -2.5}, {}, out));
  ASSERT_EQ(out.count, 1u);
  EXPECT_EQ(out.messages[0].topic, "v1/server/r1/cmd");
  EXPECT_EQ(out.messages[0].payload, std::string("\x64\x00\x06\xff", 4));
}

TEST(CommandEncoder, V1OutOfInt16IsAnErrorNeverWrapped) {
  CommandEncoder encoder{protocol::CodecLimits{}};
  CommandMessages out;
  const auto s = encoder.encode("r1", Protocol::V1, 1, kIdentity, {327.68, 0.0}, {}, out);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.reason(), protocol::RejectReason::OutOfRange);
  EXPECT_EQ(out.count, 0u);
  EXPECT_TRUE(encoder.encode("r1", Protocol::V1, 1, kIdentity, {327.67, -327.68}, {}, out));
}

TEST(CommandEncoder, V2SendsWaypointAndWholePathStartingWithTheWaypointOnce) {
  CommandEncoder encoder{protocol::CodecLimits{}};
  CommandMessages out;
  const std::vector<protocol::Point> rest{{3.0, 0.25}};
  ASSERT_TRUE(encoder.encode("r2", Protocol::V2, 7, kIdentity, {1.5, -2.0}, rest, out));
  ASSERT_EQ(out.count, 2u);
  EXPECT_EQ(out.messages[0].topic, "v2/server/r2/waypoint");
  EXPECT_EQ(out.messages[0].payload, R"({"seq":7,"x":1.5,"y":-2})");
  EXPECT_EQ(out.messages[1].topic, "v2/server/r2/path");
  EXPECT_EQ(out.messages[1].payload, R"({"seq":7,"points":[[1.5,-2],[3,0.25]]})");

  // A planner that includes the current waypoint in "remaining" gives the same path.
  const std::vector<protocol::Point> with_current{{1.5, -2.0}, {3.0, 0.25}};
  ASSERT_TRUE(encoder.encode("r2", Protocol::V2, 7, kIdentity, {1.5, -2.0}, with_current, out));
  EXPECT_EQ(out.messages[1].payload, R"({"seq":7,"points":[[1.5,-2],[3,0.25]]})");
}

TEST(CommandEncoder, BadIdsAndNonFiniteWaypointsAreErrors) {
  CommandEncoder encoder{protocol::CodecLimits{}};
  CommandMessages out;
  EXPECT_EQ(encoder.encode("a/b", Protocol::V1, 1, kIdentity, {0, 0}, {}, out).reason(),
            protocol::RejectReason::BadRobotId);
  EXPECT_EQ(encoder.encode("r", Protocol::V2, 1, kIdentity, {std::nan(""), 0}, {}, out).reason(),
            protocol::RejectReason::NonFinite);
  EXPECT_EQ(out.count, 0u);
}

}  // namespace
}  // namespace slam::gateway

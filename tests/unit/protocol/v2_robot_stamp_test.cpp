// The optional v2 "stamp" (seconds on the robot's own clock): decoded on pose, points and scan,
// absent or null as 0, refused when not a finite number >= 0; written by the robot-side encoders.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "payload.hpp"
#include "protocol/v2_robot_decode.hpp"
#include "protocol/v2_robot_encode.hpp"

namespace slam::protocol {
namespace {

using test::bytes;

TEST(RobotStamp, DecodedOnEveryObservationMessage) {
  DecodedObservation out;
  ASSERT_TRUE(decode_v2_pose(bytes(R"({"x": 1, "y": 2, "stamp": 12.5})"), {}, out).is_ok());
  EXPECT_EQ(out.robot_stamp_ns, 12'500'000'000);
  ASSERT_TRUE(decode_v2_points(bytes(R"({"stamp": 3, "points": [[1, 1]]})"), {}, out).is_ok());
  EXPECT_EQ(out.robot_stamp_ns, 3'000'000'000);
  ASSERT_TRUE(decode_v2_scan(bytes(R"({"pose": {"x": 0, "y": 0, "heading": 0}, "angle_min": 0,
                                       "angle_increment": 0.1, "ranges": [1], "max_range": 4,
                                       "stamp": 0.000000001})"),
                             {}, out)
                  .is_ok());
  EXPECT_EQ(out.robot_stamp_ns, 1);
  // An epoch in seconds keeps its microseconds.
  ASSERT_TRUE(decode_v2_pose(bytes(R"({"x": 1, "y": 2, "stamp": 1763800000.123456})"), {}, out).is_ok());
  EXPECT_NEAR(static_cast<double>(out.robot_stamp_ns - 1'763'800'000'123'456'000), 0.0, 1e3);
}

TEST(RobotStamp, AbsentOrNullIsZeroAndAReusedOutputForgetsTheLastOne) {
  DecodedObservation out;
  ASSERT_TRUE(decode_v2_pose(bytes(R"({"x": 1, "y": 2, "stamp": 7})"), {}, out).is_ok());
  ASSERT_TRUE(decode_v2_pose(bytes(R"({"x": 1, "y": 2})"), {}, out).is_ok());
  EXPECT_EQ(out.robot_stamp_ns, 0);
  ASSERT_TRUE(decode_v2_points(bytes(R"({"stamp": null, "points": []})"), {}, out).is_ok());
  EXPECT_EQ(out.robot_stamp_ns, 0);
  ASSERT_TRUE(decode_v2_pose(bytes(R"({"x": 1, "y": 2, "stamp": 0})"), {}, out).is_ok());
  EXPECT_EQ(out.robot_stamp_ns, 0);
}

TEST(RobotStamp, RejectsWhatIsNotAFiniteNonNegativeNumber) {
  struct Case {
    const char* stamp;
    RejectReason reason;
    const char* mentions;
  };
  for (const Case& c : {
           Case{"NaN", RejectReason::JsonSyntax, "byte"},  // JSON has no NaN literal
           Case{"1e999", RejectReason::NonFinite, "double"},
           Case{"-0.5", RejectReason::OutOfRange, "stamp is -0.5, must be >= 0"},
           Case{"1e10", RejectReason::OutOfRange, "stamp is"},
           Case{"\"12.5\"", RejectReason::JsonType, "stamp is string, expected a number"},
           Case{"true", RejectReason::JsonType, "stamp is boolean"},
           Case{"[12.5]", RejectReason::JsonType, "stamp is array"},
           Case{"{\"s\": 1}", RejectReason::JsonType, "stamp is object"},
       }) {
    DecodedObservation out;
    const std::string pose = std::string(R"({"x": 1, "y": 2, "stamp": )") + c.stamp + "}";
    const std::string points = std::string(R"({"points": [], "stamp": )") + c.stamp + "}";
    for (const CodecStatus& s :
         {decode_v2_pose(bytes(pose), {}, out), decode_v2_points(bytes(points), {}, out)}) {
      ASSERT_FALSE(s.is_ok()) << c.stamp;
      EXPECT_EQ(s.reason(), c.reason) << c.stamp << " -> " << s.message();
      EXPECT_NE(s.detail().find(c.mentions), std::string::npos) << c.stamp << " -> " << s.message();
    }
  }
}

TEST(RobotStamp, EncodersWriteItOnlyWhenGivenAndItRoundTrips) {
  std::string out;
  ASSERT_TRUE(encode_v2_pose({1.5, -2.0, 0.3}, {}, out, 12.25).is_ok());
  EXPECT_EQ(out, R"({"x":1.5,"y":-2,"heading":0.3,"stamp":12.25})");
  DecodedObservation decoded;
  ASSERT_TRUE(decode_v2_pose(bytes(out), {}, decoded).is_ok());
  EXPECT_EQ(decoded.robot_stamp_ns, 12'250'000'000);

  const std::vector<double> ranges = {1.0};
  V2Scan scan;
  scan.pose = {0.0, 0.0, 0.0};
  scan.angle_increment = 0.1;
  scan.ranges = ranges;
  scan.max_range = 4.0;
  ASSERT_TRUE(encode_v2_scan(scan, {}, out).is_ok());
  EXPECT_EQ(out.find("stamp"), std::string::npos) << out;
  scan.stamp = 42.5;
  ASSERT_TRUE(encode_v2_scan(scan, {}, out).is_ok());
  ASSERT_TRUE(decode_v2_scan(bytes(out), {}, decoded).is_ok()) << out;
  EXPECT_EQ(decoded.robot_stamp_ns, 42'500'000'000);
}

TEST(RobotStamp, EncodersRefuseWhatTheGatewayWouldRefuse) {
  std::string out = "stale";
  EXPECT_EQ(
      encode_v2_pose({0.0, 0.0, std::nullopt}, {}, out, std::numeric_limits<double>::quiet_NaN()).reason(),
      RejectReason::NonFinite);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(encode_v2_pose({0.0, 0.0, std::nullopt}, {}, out, -1.0).reason(), RejectReason::OutOfRange);
  V2Scan scan;
  scan.pose = {0.0, 0.0, 0.0};
  scan.max_range = 4.0;
  scan.stamp = 1e10;
  EXPECT_EQ(encode_v2_scan(scan, {}, out).reason(), RejectReason::OutOfRange);
}

}  // namespace
}  // namespace slam::protocol

// v2 robot-side encoders: exact JSON text, refusal of anything the gateway would reject, and round
// trips through the gateway's decoders.
#include "protocol/v2_robot_encode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "payload.hpp"
#include "protocol/v2_robot_decode.hpp"

namespace slam::protocol {
namespace {

using test::bytes;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(EncodeV2Pose, ExactText) {
  std::string out;
  ASSERT_TRUE(encode_v2_pose({1.5, -2.0, 0.3}, {}, out).is_ok());
  EXPECT_EQ(out, R"({"x":1.5,"y":-2,"heading":0.3})");
  ASSERT_TRUE(encode_v2_pose({0.1, 1e-7, std::nullopt}, {}, out).is_ok());
  EXPECT_EQ(out, R"({"x":0.1,"y":1e-07})");
}

TEST(EncodeV2Pose, RoundTripsExactly) {
  const V2Pose pose{1.0 / 3.0, -2.0 / 7.0, std::numbers::pi / 5.0};
  std::string out;
  ASSERT_TRUE(encode_v2_pose(pose, {}, out).is_ok());
  DecodedObservation decoded;
  ASSERT_TRUE(decode_v2_pose(bytes(out), {}, decoded).is_ok());
  EXPECT_EQ(decoded.x, pose.x);
  EXPECT_EQ(decoded.y, pose.y);
  EXPECT_TRUE(decoded.has_heading);
  EXPECT_EQ(decoded.theta, *pose.heading);
}

TEST(EncodeV2Pose, RejectsUnsendableValuesAndEmptiesOutput) {
  std::string out = "stale";
  EXPECT_EQ(encode_v2_pose({kNan, 0.0, std::nullopt}, {}, out).reason(), RejectReason::NonFinite);
  EXPECT_TRUE(out.empty());
  auto status = encode_v2_pose({0.0, 20000.0, std::nullopt}, {}, out);
  EXPECT_EQ(status.reason(), RejectReason::OutOfRange);
  EXPECT_NE(status.detail().find("y is 20000"), std::string::npos) << status.detail();
  EXPECT_EQ(encode_v2_pose({0.0, 0.0, kInf}, {}, out).reason(), RejectReason::NonFinite);
  EXPECT_EQ(encode_v2_pose({0.0, 0.0, 101.0}, {}, out).reason(), RejectReason::OutOfRange);
}

TEST(EncodeV2Scan, ExactTextInBothAngleForms) {
  const std::vector<double> ranges = {1.2, 4.0};
  V2Scan scan;
  scan.pose = {1.0, 2.0, 0.5};
  scan.angle_min = -1.5;
  scan.angle_increment = 0.25;
  scan.ranges = ranges;
  scan.max_range = 4.0;
  std::string out;
  ASSERT_TRUE(encode_v2_scan(scan, {}, out).is_ok());
  EXPECT_EQ(out, R"({"pose":{"x":1,"y":2,"heading":0.5},"angle_min":-1.5,"angle_increment":0.25,)"
                 R"("ranges":[1.2,4],"max_range":4})");
  const std::vector<double> angles = {0.0, 3.0};
  scan.angles = angles;
  scan.sensor = V2SensorOffset{0.1, 0.0, 0.0};
  ASSERT_TRUE(encode_v2_scan(scan, {}, out).is_ok());
  EXPECT_EQ(out, R"({"pose":{"x":1,"y":2,"heading":0.5},"sensor":{"x":0.1,"y":0,"theta":0},)"
                 R"("angles":[0,3],"ranges":[1.2,4],"max_range":4})");
}

TEST(EncodeV2Scan, DecodesToTheSameHitsAndMisses) {
  const std::vector<double> angles = {0.0, std::numbers::pi / 2.0, std::numbers::pi};
  const std::vector<double> ranges = {1.0, 4.0, 2.5};
  V2Scan scan;
  scan.pose = {1.0, 1.0, 0.0};
  scan.angles = angles;
  scan.ranges = ranges;
  scan.max_range = 4.0;
  std::string out;
  ASSERT_TRUE(encode_v2_scan(scan, {}, out).is_ok());
  DecodedObservation decoded;
  ASSERT_TRUE(decode_v2_scan(bytes(out), {}, decoded).is_ok()) << out;
  ASSERT_EQ(decoded.hits.size(), 2u);
  ASSERT_EQ(decoded.misses.size(), 1u);
  EXPECT_NEAR(decoded.hits[0].x, 2.0, 1e-12);
  EXPECT_NEAR(decoded.hits[0].y, 1.0, 1e-12);
  EXPECT_NEAR(decoded.hits[1].x, -1.5, 1e-12);
  EXPECT_NEAR(decoded.misses[0].y, 5.0, 1e-12);
}

TEST(EncodeV2Scan, RejectsWhatTheGatewayWouldReject) {
  const std::vector<double> ranges = {1.0, 2.0};
  V2Scan good;
  good.pose = {0.0, 0.0, 0.0};
  good.ranges = ranges;
  good.max_range = 4.0;
  std::string out = "stale";

  V2Scan s = good;
  s.pose.heading.reset();
  EXPECT_EQ(encode_v2_scan(s, {}, out).reason(), RejectReason::MissingField);
  EXPECT_TRUE(out.empty());
  s = good;
  s.max_range = 0.0;
  EXPECT_EQ(encode_v2_scan(s, {}, out).reason(), RejectReason::OutOfRange);
  const std::vector<double> negative = {1.0, -0.5};
  s = good;
  s.ranges = negative;
  auto status = encode_v2_scan(s, {}, out);
  EXPECT_EQ(status.reason(), RejectReason::OutOfRange);
  EXPECT_NE(status.detail().find("ranges[1]"), std::string::npos) << status.detail();
  const std::vector<double> infinite = {kInf, 1.0};
  s.ranges = infinite;
  EXPECT_EQ(encode_v2_scan(s, {}, out).reason(), RejectReason::NonFinite);
  const std::vector<double> one_angle = {0.0};
  s = good;
  s.angles = one_angle;
  EXPECT_EQ(encode_v2_scan(s, {}, out).reason(), RejectReason::BadLength);
  s = good;
  s.sensor = V2SensorOffset{0.0, 0.0, kNan};
  EXPECT_EQ(encode_v2_scan(s, {}, out).reason(), RejectReason::NonFinite);
  CodecLimits small;
  small.max_points = 1;
  EXPECT_EQ(encode_v2_scan(good, small, out).reason(), RejectReason::TooManyPoints);
  EXPECT_TRUE(out.empty());
}

TEST(EncodeV2Status, ExactTextEscapesAndRoundTrip) {
  std::string out;
  ASSERT_TRUE(encode_v2_status({"exploring", 0.82}, out).is_ok());
  EXPECT_EQ(out, R"({"battery":0.82,"state":"exploring"})");
  ASSERT_TRUE(encode_v2_status({"say \"hi\" \\ caf\xC3\xA9", std::nullopt}, out).is_ok());
  EXPECT_EQ(out, "{\"state\":\"say \\\"hi\\\" \\\\ caf\xC3\xA9\"}");
  DecodedStatus decoded;
  ASSERT_TRUE(decode_v2_status(bytes(out), {}, decoded).is_ok());
  EXPECT_EQ(decoded.state, "say \"hi\" \\ caf\xC3\xA9");
  EXPECT_LT(decoded.battery, 0.0f);
}

TEST(EncodeV2Status, RejectsBadStateAndBattery) {
  std::string out = "stale";
  EXPECT_EQ(encode_v2_status({"", std::nullopt}, out).reason(), RejectReason::BadText);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(encode_v2_status({std::string(33, 'a'), std::nullopt}, out).reason(), RejectReason::BadText);
  EXPECT_EQ(encode_v2_status({"tab\there", std::nullopt}, out).reason(), RejectReason::BadText);
  EXPECT_EQ(encode_v2_status({"bad \xC3", std::nullopt}, out).reason(), RejectReason::BadText);
  EXPECT_EQ(encode_v2_status({"ok", 1.5}, out).reason(), RejectReason::OutOfRange);
  EXPECT_EQ(encode_v2_status({"ok", -0.1}, out).reason(), RejectReason::OutOfRange);
  EXPECT_EQ(encode_v2_status({"ok", kNan}, out).reason(), RejectReason::NonFinite);
}

TEST(V2OfflineStatus, IsTheLastWillTheGatewayRecognises) {
  DecodedStatus decoded;
  ASSERT_TRUE(decode_v2_status(bytes(kV2OfflineStatus), {}, decoded).is_ok());
  EXPECT_TRUE(decoded.offline);
  std::string out;
  ASSERT_TRUE(encode_v2_status({"offline", std::nullopt}, out).is_ok());
  EXPECT_EQ(out, kV2OfflineStatus);
}

}  // namespace
}  // namespace slam::protocol

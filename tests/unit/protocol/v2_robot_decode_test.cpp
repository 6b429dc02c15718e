// v2 robot -> server JSON: each message kind, the scan transform, and every rejection kind.
#include "protocol/v2_robot_decode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "payload.hpp"

namespace slam::protocol {
namespace {

using test::bytes;
constexpr double kPi = std::numbers::pi;

CodecStatus pose(std::string_view json, DecodedObservation& out) {
  return decode_v2_pose(bytes(json), {}, out);
}
CodecStatus points(std::string_view json, DecodedObservation& out) {
  return decode_v2_points(bytes(json), {}, out);
}
CodecStatus scan(std::string_view json, DecodedObservation& out) {
  return decode_v2_scan(bytes(json), {}, out);
}
CodecStatus status(std::string_view json, DecodedStatus& out) {
  return decode_v2_status(bytes(json), {}, out);
}

TEST(DecodeV2Pose, WithAndWithoutHeading) {
  DecodedObservation out;
  ASSERT_TRUE(pose(R"({"x": 1.5, "y": -2, "heading": 0.25})", out).is_ok());
  EXPECT_DOUBLE_EQ(out.x, 1.5);
  EXPECT_DOUBLE_EQ(out.y, -2.0);
  EXPECT_DOUBLE_EQ(out.theta, 0.25);
  EXPECT_TRUE(out.has_pose);
  EXPECT_TRUE(out.has_heading);
  ASSERT_TRUE(pose(R"({"x": 1, "y": 2})", out).is_ok());
  EXPECT_FALSE(out.has_heading);
  ASSERT_TRUE(pose(R"({"x": 1, "y": 2, "heading": null, "future_field": [1, 2]})", out).is_ok());
  EXPECT_FALSE(out.has_heading);
}

TEST(DecodeV2Pose, Rejections) {
  DecodedObservation out;
  struct Case {
    const char* json;
    RejectReason reason;
    const char* mentions;
  };
  for (const Case& c : {
           Case{R"({"x": 1, "y": )", RejectReason::JsonSyntax, "byte"},
           Case{R"({"x": 1, "y": 2} trailing)", RejectReason::JsonSyntax, "byte"},
           Case{R"({"x": NaN, "y": 2})", RejectReason::JsonSyntax, "byte"},
           Case{"{\"x\": 1, \"y\": 2, \"s\": \"\xFF\"}", RejectReason::JsonSyntax, "byte"},
           Case{R"([1, 2])", RejectReason::JsonType, "top level is array"},
           Case{R"("pose")", RejectReason::JsonType, "top level is string"},
           Case{R"({"x": "1", "y": 2})", RejectReason::JsonType, "x is string"},
           Case{R"({"x": 1, "y": true})", RejectReason::JsonType, "y is boolean"},
           Case{R"({"x": 1, "y": null})", RejectReason::JsonType, "y is null"},
           Case{R"({"x": 1})", RejectReason::MissingField, "y is missing"},
           Case{R"({"x": 1e999, "y": 2})", RejectReason::NonFinite, "double"},
           Case{R"({"x": 10000.5, "y": 2})", RejectReason::OutOfRange, "x is 10000.5"},
           Case{R"({"x": 1, "y": -18446744073709551615})", RejectReason::OutOfRange, "y"},
           Case{R"({"x": 1, "y": 2, "heading": 101})", RejectReason::OutOfRange, "heading"},
           Case{R"({"x": 1, "y": 2, "heading": "north"})", RejectReason::JsonType, "heading is string"},
       }) {
    const CodecStatus s = pose(c.json, out);
    ASSERT_FALSE(s.is_ok()) << c.json;
    EXPECT_EQ(s.reason(), c.reason) << c.json << " -> " << s.message();
    EXPECT_NE(s.detail().find(c.mentions), std::string::npos) << c.json << " -> " << s.message();
  }
  EXPECT_EQ(decode_v2_pose({}, {}, out).reason(), RejectReason::EmptyPayload);
  CodecLimits small;
  small.max_payload_bytes = 8;
  EXPECT_EQ(decode_v2_pose(bytes(R"({"x": 1, "y": 2})"), small, out).reason(), RejectReason::Oversized);
}

TEST(DecodeV2Pose, DeepNestingIsRejectedWithoutCrashing) {
  DecodedObservation out;
  const std::string open(100'000, '[');
  EXPECT_EQ(pose(open, out).reason(), RejectReason::JsonSyntax);
  EXPECT_EQ(pose(open + std::string(100'000, ']'), out).reason(), RejectReason::JsonType);
  const std::string nested = R"({"x": 1, "y": 2, "extra": )" + open + std::string(100'000, ']') + "}";
  EXPECT_TRUE(pose(nested, out).is_ok());  // unknown members are ignored, however deep
}

TEST(DecodeV2Points, WithAndWithoutPose) {
  DecodedObservation out;
  ASSERT_TRUE(
      points(R"({"pose": {"x": 1, "y": 2, "heading": 3}, "points": [[0.5, -1], [7, 8]]})", out).is_ok());
  EXPECT_TRUE(out.has_pose);
  EXPECT_TRUE(out.has_heading);
  EXPECT_DOUBLE_EQ(out.theta, 3.0);
  ASSERT_EQ(out.hits.size(), 2u);
  EXPECT_EQ(out.hits[0], (Point{0.5, -1.0}));
  EXPECT_EQ(out.hits[1], (Point{7.0, 8.0}));
  EXPECT_TRUE(out.misses.empty());

  ASSERT_TRUE(points(R"({"points": [[1, 1]]})", out).is_ok());
  EXPECT_FALSE(out.has_pose);
  EXPECT_EQ(out.hits.size(), 1u);
  ASSERT_TRUE(points(R"({"pose": null, "points": []})", out).is_ok());
  EXPECT_TRUE(out.hits.empty());
}

TEST(DecodeV2Points, Rejections) {
  DecodedObservation out;
  struct Case {
    const char* json;
    RejectReason reason;
    const char* mentions;
  };
  for (const Case& c : {
           Case{R"({"pose": {"x": 1, "y": 2}})", RejectReason::MissingField, "points is missing"},
           Case{R"({"points": {"x": 1}})", RejectReason::JsonType, "points is object"},
           Case{R"({"points": [[1, 2], [3]]})", RejectReason::JsonType, "points[1] is array of 1"},
           Case{R"({"points": [[1, 2], 3]})", RejectReason::JsonType, "points[1] is number"},
           Case{R"({"points": [[1, "2"]]})", RejectReason::JsonType, "points[0].y is string"},
           Case{R"({"points": [[1, 2, 3]]})", RejectReason::JsonType, "points[0]"},
           Case{R"({"points": [[-20000, 2]]})", RejectReason::OutOfRange, "points[0].x"},
           Case{R"({"pose": [1, 2], "points": []})", RejectReason::JsonType, "pose is array"},
           Case{R"({"pose": {"x": 1}, "points": []})", RejectReason::MissingField, "pose.y is missing"},
       }) {
    const CodecStatus s = points(c.json, out);
    ASSERT_FALSE(s.is_ok()) << c.json;
    EXPECT_EQ(s.reason(), c.reason) << c.json << " -> " << s.message();
    EXPECT_NE(s.detail().find(c.mentions), std::string::npos) << c.json << " -> " << s.message();
  }
  CodecLimits few;
  few.max_points = 2;
  EXPECT_TRUE(decode_v2_points(bytes(R"({"points": [[1, 2], [3, 4]]})"), few, out).is_ok());
  EXPECT_EQ(decode_v2_points(bytes(R"({"points": [[1, 2], [3, 4], [5, 6]]})"), few, out).reason(),
            RejectReason::TooManyPoints);
}

TEST(DecodeV2Scan, HitsAndMissesInTheMapFrame) {
  // Robot at (1, 2) facing +y; beams at -90, 0, +90 degrees relative to the robot.
  DecodedObservation out;
  const CodecStatus s = scan(R"({"pose": {"x": 1, "y": 2, "heading": 1.5707963267948966},
      "angle_min": -1.5707963267948966, "angle_increment": 1.5707963267948966,
      "ranges": [1.0, null, 5.0], "max_range": 4.0})",
                             out);
  ASSERT_TRUE(s.is_ok()) << s.message();
  EXPECT_TRUE(out.has_pose);
  EXPECT_TRUE(out.has_heading);
  EXPECT_DOUBLE_EQ(out.x, 1.0);
  EXPECT_DOUBLE_EQ(out.y, 2.0);
  EXPECT_DOUBLE_EQ(out.theta, kPi / 2);
  ASSERT_EQ(out.hits.size(), 1u);  // beam 0: -90 deg from +y is +x
  EXPECT_NEAR(out.hits[0].x, 2.0, 1e-12);
  EXPECT_NEAR(out.hits[0].y, 2.0, 1e-12);
  ASSERT_EQ(out.misses.size(), 2u);  // null -> miss straight ahead; 5 >= 4 -> miss to the left
  EXPECT_NEAR(out.misses[0].x, 1.0, 1e-12);
  EXPECT_NEAR(out.misses[0].y, 6.0, 1e-12);
  EXPECT_NEAR(out.misses[1].x, -3.0, 1e-12);
  EXPECT_NEAR(out.misses[1].y, 2.0, 1e-12);
}

TEST(DecodeV2Scan, RangeEqualToMaxIsAMiss) {
  DecodedObservation out;
  ASSERT_TRUE(scan(R"({"pose": {"x": 0, "y": 0, "heading": 0}, "angles": [0, 0],
      "ranges": [4.0, 3.999], "max_range": 4.0})",
                   out)
                  .is_ok());
  EXPECT_EQ(out.misses.size(), 1u);
  EXPECT_EQ(out.hits.size(), 1u);
}

TEST(DecodeV2Scan, AZeroRangeIsAnErrorReadingLeftOut) {
  // Many lasers report 0 for "no measurement": no obstacle at the sensor, no free space; counted.
  DecodedObservation out;
  ASSERT_TRUE(scan(R"({"pose": {"x": 0, "y": 0, "heading": 0}, "angles": [0, 0.5, 1, 1.5],
      "ranges": [0, 2.0, 0.0, 9.0], "max_range": 4.0})",
                   out)
                  .is_ok());
  ASSERT_EQ(out.hits.size(), 1u);
  EXPECT_NEAR(out.hits[0].x, 2.0 * std::cos(0.5), 1e-12);
  EXPECT_EQ(out.misses.size(), 1u);  // 9 m: beyond the maximum, no return
  EXPECT_EQ(out.error_beams, 2u);
  // A negative range is no reading at all: the message is refused.
  EXPECT_EQ(
      scan(R"({"pose": {"x": 0, "y": 0, "heading": 0}, "angles": [0], "ranges": [-1], "max_range": 4})", out)
          .reason(),
      RejectReason::OutOfRange);
  EXPECT_EQ(out.error_beams, 0u);
}

TEST(DecodeV2Scan, FreeSpaceWithoutAReturnEndsAtTheFreeRange) {
  // A 30 m laser: a return at 20 m stays a hit; a beam without one clears 5 m only (the default).
  DecodedObservation out;
  ASSERT_TRUE(scan(R"({"pose": {"x": 0, "y": 0, "heading": 0}, "angles": [0, 1.5707963267948966],
      "ranges": [20.0, null], "max_range": 30.0})",
                   out)
                  .is_ok());
  ASSERT_EQ(out.hits.size(), 1u);
  EXPECT_NEAR(out.hits[0].x, 20.0, 1e-12);
  ASSERT_EQ(out.misses.size(), 1u);
  EXPECT_NEAR(out.misses[0].y, CodecLimits{}.scan_free_range_m, 1e-12);
  CodecLimits bad;
  bad.scan_free_range_m = 0.0;
  EXPECT_FALSE(validate(bad).is_ok());
}

TEST(DecodeV2Scan, SensorOffsetMovesTheOrigin) {
  // Robot at (10, 0) facing +y with the sensor mounted 0.5 m ahead, turned +90 degrees (facing -x).
  DecodedObservation out;
  const CodecStatus s = scan(R"({"pose": {"x": 10, "y": 0, "heading": 1.5707963267948966},
      "sensor": {"x": 0.5, "theta": 1.5707963267948966},
      "angles": [0.0], "ranges": [2.0], "max_range": 8})",
                             out);
  ASSERT_TRUE(s.is_ok()) << s.message();
  EXPECT_NEAR(out.x, 10.0, 1e-12);
  EXPECT_NEAR(out.y, 0.5, 1e-12);
  EXPECT_NEAR(out.theta, kPi, 1e-12);
  ASSERT_EQ(out.hits.size(), 1u);
  EXPECT_NEAR(out.hits[0].x, 8.0, 1e-12);
  EXPECT_NEAR(out.hits[0].y, 0.5, 1e-12);
}

TEST(DecodeV2Scan, EmptyScanIsAPoseUpdate) {
  DecodedObservation out;
  ASSERT_TRUE(
      scan(R"({"pose": {"x": 0, "y": 0, "heading": 0}, "angles": [], "ranges": [], "max_range": 1})", out)
          .is_ok());
  EXPECT_TRUE(out.hits.empty());
  EXPECT_TRUE(out.misses.empty());
}

TEST(DecodeV2Scan, Rejections) {
  DecodedObservation out;
  const std::string p = R"("pose": {"x": 0, "y": 0, "heading": 0}, )";
  const std::string cases[][3] = {
      {R"({"angles": [0], "ranges": [1], "max_range": 2})", "missing_field", "pose is missing"},
      {R"({"pose": {"x": 0, "y": 0}, "angles": [0], "ranges": [1], "max_range": 2})", "missing_field",
       "pose.heading is missing"},
      {"{" + p + R"("angles": [0], "ranges": [1]})", "missing_field", "max_range is missing"},
      {"{" + p + R"("angles": [0], "max_range": 2})", "missing_field", "ranges is missing"},
      {"{" + p + R"("ranges": [1], "max_range": 2})", "missing_field", "angle_min and angle_increment"},
      {"{" + p + R"("angle_min": 0, "ranges": [1], "max_range": 2})", "missing_field",
       "angle_increment is missing"},
      {"{" + p + R"("angles": [0], "angle_min": 0, "ranges": [1], "max_range": 2})", "json_type", "not both"},
      {"{" + p + R"("angles": [0, 1], "ranges": [1], "max_range": 2})", "bad_length", "angles has 2"},
      {"{" + p + R"("angles": 0, "ranges": [1], "max_range": 2})", "json_type", "angles is number"},
      {"{" + p + R"("angles": ["a"], "ranges": [1], "max_range": 2})", "json_type", "angles[0] is string"},
      {"{" + p + R"("angles": [0], "ranges": "1", "max_range": 2})", "json_type", "ranges is string"},
      {"{" + p + R"("angles": [0], "ranges": [true], "max_range": 2})", "json_type", "ranges[0] is boolean"},
      {"{" + p + R"("angles": [0], "ranges": [-0.5], "max_range": 2})", "out_of_range", "ranges[0] is -0.5"},
      {"{" + p + R"("angles": [0], "ranges": [1e999], "max_range": 2})", "non_finite", "double"},
      {"{" + p + R"("angles": [0], "ranges": [1], "max_range": 0})", "out_of_range", "max_range is 0"},
      {"{" + p + R"("angles": [0], "ranges": [1], "max_range": -3})", "out_of_range", "max_range is -3"},
      {"{" + p + R"("angles": [0], "ranges": [1], "max_range": 20000})", "out_of_range", "max_range"},
      {"{" + p + R"("angles": [500], "ranges": [1], "max_range": 2})", "out_of_range", "angles[0]"},
      {"{" + p + R"("angle_min": 0, "angle_increment": "x", "ranges": [1], "max_range": 2})", "json_type",
       "angle_increment is string"},
      {"{" + p + R"("sensor": [0, 0], "angles": [0], "ranges": [1], "max_range": 2})", "json_type",
       "sensor is array"},
      {"{" + p + R"("sensor": {"theta": 1000}, "angles": [0], "ranges": [1], "max_range": 2})",
       "out_of_range", "sensor.theta"},
      {R"({"pose": {"x": 9999, "y": 0, "heading": 0}, "angles": [0], "ranges": [5], "max_range": 9})",
       "out_of_range", "beam 0 ends at"},
      {R"({"pose": {"x": 9999, "y": 0, "heading": 0}, "sensor": {"x": 5}, "angles": [], "ranges": [],
          "max_range": 9})",
       "out_of_range", "sensor origin"},
  };
  for (const auto& c : cases) {
    const CodecStatus s = scan(c[0], out);
    ASSERT_FALSE(s.is_ok()) << c[0];
    EXPECT_EQ(reason_name(s.reason()), c[1]) << c[0] << " -> " << s.message();
    EXPECT_NE(s.detail().find(c[2]), std::string::npos) << c[0] << " -> " << s.message();
  }
  CodecLimits few;
  few.max_points = 2;
  EXPECT_EQ(decode_v2_scan(bytes("{" + p + R"("angles": [0, 0, 0], "ranges": [1, 1, 1], "max_range": 2})"),
                           few, out)
                .reason(),
            RejectReason::TooManyPoints);
}

TEST(DecodeV2Status, BatteryAndState) {
  DecodedStatus out;
  ASSERT_TRUE(status(R"({"battery": 0.75, "state": "exploring"})", out).is_ok());
  EXPECT_FLOAT_EQ(out.battery, 0.75f);
  EXPECT_EQ(out.state, "exploring");
  EXPECT_FALSE(out.offline);
  ASSERT_TRUE(status(R"({"state": "idle"})", out).is_ok());
  EXPECT_LT(out.battery, 0.0f);
  ASSERT_TRUE(status(R"({"battery": 0, "state": "charging"})", out).is_ok());
  EXPECT_EQ(out.battery, 0.0f);
  ASSERT_TRUE(status(R"({"battery": 1, "state": "Übung"})", out).is_ok());
  EXPECT_EQ(out.battery, 1.0f);
}

TEST(DecodeV2Status, LastWillIsOffline) {
  DecodedStatus out;
  ASSERT_TRUE(status(R"({"state": "offline"})", out).is_ok());
  EXPECT_TRUE(out.offline);
  EXPECT_EQ(out.state, "offline");
}

TEST(DecodeV2Status, Rejections) {
  DecodedStatus out;
  const std::string long_state = R"({"state": ")" + std::string(33, 's') + "\"}";
  const std::string cases[][3] = {
      {R"({"battery": 0.5})", "missing_field", "state is missing"},
      {R"({"state": 3})", "json_type", "state is number"},
      {R"({"state": ""})", "bad_text", "state is empty"},
      {long_state, "bad_text", "33 bytes"},
      {R"({"state": "a\nb"})", "bad_text", "control character"},
      {R"({"state": "a\u0000b"})", "bad_text", "control character"},
      {R"({"state": "ok", "battery": 1.5})", "out_of_range", "battery"},
      {R"({"state": "ok", "battery": -0.1})", "out_of_range", "battery"},
      {R"({"state": "ok", "battery": "full"})", "json_type", "battery is string"},
      {R"({"state": "\ud800"})", "json_syntax", "byte"},
  };
  for (const auto& c : cases) {
    const CodecStatus s = status(c[0], out);
    ASSERT_FALSE(s.is_ok()) << c[0];
    EXPECT_EQ(reason_name(s.reason()), c[1]) << c[0] << " -> " << s.message();
    EXPECT_NE(s.detail().find(c[2]), std::string::npos) << c[0] << " -> " << s.message();
  }
  EXPECT_TRUE(status(R"({"state": ")" + std::string(32, 's') + "\"}", out).is_ok());
}

}  // namespace
}  // namespace slam::protocol

// v1 waypoint decoding on the robot side: exact bytes, strict length, and round trips with the
// gateway's encoder.
#include "protocol/v1_robot_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "protocol/v1_codec.hpp"

namespace slam::protocol {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(DecodeV1Waypoint, DocumentedExample) {
  const Bytes payload = {0x64, 0x00, 0x06, 0xFF};  // (100, -250) cm
  Point out;
  ASSERT_TRUE(decode_v1_waypoint(payload, CodecLimits{}, out).is_ok());
  EXPECT_DOUBLE_EQ(out.x, 1.0);
  EXPECT_DOUBLE_EQ(out.y, -2.5);
}

TEST(DecodeV1Waypoint, Int16Extremes) {
  const Bytes payload = {0xFF, 0x7F, 0x00, 0x80};
  Point out;
  ASSERT_TRUE(decode_v1_waypoint(payload, CodecLimits{}, out).is_ok());
  EXPECT_DOUBLE_EQ(out.x, 327.67);
  EXPECT_DOUBLE_EQ(out.y, -327.68);
}

TEST(DecodeV1Waypoint, RejectsEveryLengthButFourAndKeepsTheOutput) {
  const Point before{7.0, 8.0};
  Point out = before;
  auto status = decode_v1_waypoint({}, CodecLimits{}, out);
  ASSERT_FALSE(status.is_ok());
  EXPECT_EQ(status.reason(), RejectReason::EmptyPayload);
  for (std::size_t n : {1u, 2u, 3u, 5u, 8u, 12u}) {
    const Bytes payload(n, 0x01);
    status = decode_v1_waypoint(payload, CodecLimits{}, out);
    ASSERT_FALSE(status.is_ok()) << n;
    EXPECT_EQ(status.reason(), RejectReason::BadLength) << n;
    EXPECT_NE(status.detail().find(std::to_string(n) + " bytes"), std::string::npos) << status.detail();
  }
  EXPECT_EQ(out, before);
}

TEST(DecodeV1Waypoint, RejectsBadScale) {
  const Bytes payload = {0, 0, 0, 0};
  Point out;
  CodecLimits limits;
  limits.units_per_meter = 0.0;
  EXPECT_EQ(decode_v1_waypoint(payload, limits, out).reason(), RejectReason::OutOfRange);
  limits.units_per_meter = std::numeric_limits<double>::infinity();
  EXPECT_EQ(decode_v1_waypoint(payload, limits, out).reason(), RejectReason::NonFinite);
}

TEST(DecodeV1Waypoint, RoundTripsTheGatewayEncoderAtAnyScale) {
  for (double units : {100.0, 1000.0, 1.0}) {
    CodecLimits limits;
    limits.units_per_meter = units;
    for (const Point p : {Point{0.0, 0.0}, Point{1.25, -3.5}, Point{-20.0, 31.0}}) {
      std::array<std::uint8_t, kV1PairBytes> bytes{};
      ASSERT_TRUE(encode_v1_waypoint(p, units, bytes).is_ok());
      Point out;
      ASSERT_TRUE(decode_v1_waypoint(bytes, limits, out).is_ok());
      EXPECT_NEAR(out.x, p.x, 0.5 / units);
      EXPECT_NEAR(out.y, p.y, 0.5 / units);
    }
  }
}

}  // namespace
}  // namespace slam::protocol

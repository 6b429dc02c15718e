// v1 binary codec: exact bytes (compatibility with 2019 robots), every rejection, round trips.
#include "protocol/v1_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace slam::protocol {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(DecodeV1, PositionOnly) {
  const Bytes payload = {0x64, 0x00, 0x06, 0xFF};  // (100, -250) cm
  DecodedObservation out;
  ASSERT_TRUE(decode_v1(payload, CodecLimits{}, out).is_ok());
  EXPECT_DOUBLE_EQ(out.x, 1.0);
  EXPECT_DOUBLE_EQ(out.y, -2.5);
  EXPECT_TRUE(out.has_pose);
  EXPECT_FALSE(out.has_heading);
  EXPECT_TRUE(out.hits.empty());
  EXPECT_TRUE(out.misses.empty());
}

TEST(DecodeV1, PositionAndObstacles) {
  const Bytes payload = {0x00, 0x00, 0x00, 0x00,   // position (0, 0)
                         0xFF, 0x7F, 0x00, 0x80,   // (32767, -32768)
                         0x01, 0x00, 0xFF, 0xFF};  // (1, -1)
  DecodedObservation out;
  ASSERT_TRUE(decode_v1(payload, CodecLimits{}, out).is_ok());
  ASSERT_EQ(out.hits.size(), 2u);
  EXPECT_DOUBLE_EQ(out.hits[0].x, 327.67);
  EXPECT_DOUBLE_EQ(out.hits[0].y, -327.68);
  EXPECT_DOUBLE_EQ(out.hits[1].x, 0.01);
  EXPECT_DOUBLE_EQ(out.hits[1].y, -0.01);
}

TEST(DecodeV1, UnitsPerMeterScales) {
  CodecLimits millimetres;
  millimetres.units_per_meter = 1000.0;
  const Bytes payload = {0xE8, 0x03, 0x18, 0xFC};  // (1000, -1000)
  DecodedObservation out;
  ASSERT_TRUE(decode_v1(payload, millimetres, out).is_ok());
  EXPECT_DOUBLE_EQ(out.x, 1.0);
  EXPECT_DOUBLE_EQ(out.y, -1.0);
}

TEST(DecodeV1, Rejections) {
  DecodedObservation out;
  const CodecLimits limits;
  EXPECT_EQ(decode_v1({}, limits, out).reason(), RejectReason::EmptyPayload);
  for (std::size_t n : {1u, 2u, 3u, 5u, 7u}) {
    const CodecStatus status = decode_v1(Bytes(n, 0), limits, out);
    EXPECT_EQ(status.reason(), RejectReason::BadLength) << n;
    EXPECT_NE(status.detail().find(std::to_string(n) + " bytes"), std::string::npos) << status.detail();
  }
  CodecLimits few;
  few.max_points = 2;
  EXPECT_TRUE(decode_v1(Bytes(12, 0), few, out).is_ok());  // position + 2 obstacles
  EXPECT_EQ(decode_v1(Bytes(16, 0), few, out).reason(), RejectReason::TooManyPoints);
  CodecLimits small;
  small.max_payload_bytes = 8;
  EXPECT_EQ(decode_v1(Bytes(12, 0), small, out).reason(), RejectReason::Oversized);
}

TEST(DecodeV1, RejectsBadUnits) {
  DecodedObservation out;
  const Bytes payload(4, 0);
  CodecLimits limits;
  limits.units_per_meter = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(decode_v1(payload, limits, out).reason(), RejectReason::NonFinite);
  limits.units_per_meter = std::numeric_limits<double>::infinity();
  EXPECT_EQ(decode_v1(payload, limits, out).reason(), RejectReason::NonFinite);
  limits.units_per_meter = 0.0;
  EXPECT_EQ(decode_v1(payload, limits, out).reason(), RejectReason::OutOfRange);
}

TEST(DecodeV1, RejectsCoordinatesBeyondTheBound) {
  CodecLimits limits;
  limits.units_per_meter = 1.0;  // int16 extremes become +/-32 km
  limits.max_abs_coordinate_m = 100.0;
  DecodedObservation out;
  EXPECT_TRUE(decode_v1(Bytes{0x64, 0x00, 0x9C, 0xFF}, limits, out).is_ok());  // (100, -100): inclusive
  const CodecStatus status = decode_v1(Bytes{0x00, 0x00, 0x00, 0x00, 0x65, 0x00, 0x00, 0x00}, limits, out);
  EXPECT_EQ(status.reason(), RejectReason::OutOfRange);
  EXPECT_NE(status.detail().find("pair 1"), std::string::npos) << status.detail();
}

TEST(DecodeV1, ReusedOutputDoesNotReallocate) {
  Bytes big(4 * 101, 0x01);
  DecodedObservation out;
  ASSERT_TRUE(decode_v1(big, CodecLimits{}, out).is_ok());
  const Point* storage = out.hits.data();
  ASSERT_TRUE(decode_v1(Bytes(4 * 51, 0x02), CodecLimits{}, out).is_ok());
  EXPECT_EQ(out.hits.size(), 50u);
  ASSERT_TRUE(decode_v1(big, CodecLimits{}, out).is_ok());
  EXPECT_EQ(out.hits.data(), storage);
}

TEST(EncodeV1Waypoint, ExactBytes) {
  std::array<std::uint8_t, 4> out{};
  ASSERT_TRUE(encode_v1_waypoint({1.0, -2.5}, 100.0, out).is_ok());
  EXPECT_EQ(out, (std::array<std::uint8_t, 4>{0x64, 0x00, 0x06, 0xFF}));
  ASSERT_TRUE(encode_v1_waypoint({327.67, -327.68}, 100.0, out).is_ok());
  EXPECT_EQ(out, (std::array<std::uint8_t, 4>{0xFF, 0x7F, 0x00, 0x80}));
  ASSERT_TRUE(encode_v1_waypoint({0.0, -0.0}, 100.0, out).is_ok());
  EXPECT_EQ(out, (std::array<std::uint8_t, 4>{0, 0, 0, 0}));
}

TEST(EncodeV1Waypoint, RoundsToNearestHalvesAwayFromZero) {
  std::array<std::uint8_t, 4> out{};
  ASSERT_TRUE(encode_v1_waypoint({0.014, 0.016}, 100.0, out).is_ok());  // 1.4 -> 1, 1.6 -> 2
  EXPECT_EQ(out, (std::array<std::uint8_t, 4>{0x01, 0x00, 0x02, 0x00}));
  ASSERT_TRUE(encode_v1_waypoint({2.5, -2.5}, 1.0, out).is_ok());  // 3, -3
  EXPECT_EQ(out, (std::array<std::uint8_t, 4>{0x03, 0x00, 0xFD, 0xFF}));
}

TEST(EncodeV1Waypoint, OutOfRangeIsAnErrorNeverWrapped) {
  std::array<std::uint8_t, 4> out{0xAA, 0xAA, 0xAA, 0xAA};
  const CodecStatus high = encode_v1_waypoint({327.68, 0.0}, 100.0, out);
  EXPECT_EQ(high.reason(), RejectReason::OutOfRange);
  EXPECT_NE(high.detail().find("waypoint x"), std::string::npos) << high.detail();
  EXPECT_EQ(encode_v1_waypoint({0.0, -327.69}, 100.0, out).reason(), RejectReason::OutOfRange);
  EXPECT_EQ(encode_v1_waypoint({1e300, 0.0}, 100.0, out).reason(), RejectReason::OutOfRange);
  EXPECT_EQ(out, (std::array<std::uint8_t, 4>{0xAA, 0xAA, 0xAA, 0xAA}));  // untouched on error
  // The bound applies after rounding: -32768.4 units rounds into range, -32768.6 does not.
  EXPECT_TRUE(encode_v1_waypoint({-32768.4, 0.0}, 1.0, out).is_ok());
  EXPECT_EQ(encode_v1_waypoint({-32768.6, 0.0}, 1.0, out).reason(), RejectReason::OutOfRange);
}

TEST(EncodeV1Waypoint, NonFinite) {
  std::array<std::uint8_t, 4> out{};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(encode_v1_waypoint({nan, 0.0}, 100.0, out).reason(), RejectReason::NonFinite);
  EXPECT_EQ(encode_v1_waypoint({0.0, -inf}, 100.0, out).reason(), RejectReason::NonFinite);
  EXPECT_EQ(encode_v1_waypoint({0.0, 0.0}, nan, out).reason(), RejectReason::NonFinite);
  EXPECT_EQ(encode_v1_waypoint({0.0, 0.0}, -1.0, out).reason(), RejectReason::OutOfRange);
}

TEST(EncodeV1Adv, RoundTripsThroughDecode) {
  const std::vector<Point> obstacles = {{1.23, -4.56}, {-300.0, 300.0}, {0.0, 0.01}};
  std::vector<std::uint8_t> payload;
  ASSERT_TRUE(encode_v1_adv({12.34, -0.05}, obstacles, 100.0, payload).is_ok());
  ASSERT_EQ(payload.size(), 16u);
  DecodedObservation out;
  ASSERT_TRUE(decode_v1(payload, CodecLimits{}, out).is_ok());
  EXPECT_NEAR(out.x, 12.34, 1e-9);
  EXPECT_NEAR(out.y, -0.05, 1e-9);
  ASSERT_EQ(out.hits.size(), obstacles.size());
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    EXPECT_NEAR(out.hits[i].x, obstacles[i].x, 1e-9);
    EXPECT_NEAR(out.hits[i].y, obstacles[i].y, 1e-9);
  }
}

TEST(EncodeV1Adv, WaypointBytesDecodeAsAPosition) {
  std::array<std::uint8_t, 4> bytes{};
  ASSERT_TRUE(encode_v1_waypoint({-1.5, 2.25}, 100.0, bytes).is_ok());
  DecodedObservation out;
  ASSERT_TRUE(decode_v1(bytes, CodecLimits{}, out).is_ok());
  EXPECT_DOUBLE_EQ(out.x, -1.5);
  EXPECT_DOUBLE_EQ(out.y, 2.25);
}

TEST(EncodeV1Adv, ErrorNamesTheObstacleAndEmptiesOutput) {
  const std::vector<Point> obstacles = {{0.0, 0.0}, {0.0, 400.0}};
  std::vector<std::uint8_t> payload = {1, 2, 3};
  const CodecStatus status = encode_v1_adv({0.0, 0.0}, obstacles, 100.0, payload);
  EXPECT_EQ(status.reason(), RejectReason::OutOfRange);
  EXPECT_NE(status.detail().find("obstacle 1"), std::string::npos) << status.detail();
  EXPECT_TRUE(payload.empty());
}

}  // namespace
}  // namespace slam::protocol

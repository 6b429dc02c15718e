// v2 waypoint and path: exact JSON text, rejection of unsendable values, encode -> decode round trips.
#include "protocol/v2_server_codec.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "payload.hpp"

namespace slam::protocol {
namespace {

using test::bytes;

TEST(EncodeV2Waypoint, ExactText) {
  std::string out;
  ASSERT_TRUE(encode_v2_waypoint({7, {1.5, -2.0}}, {}, out).is_ok());
  EXPECT_EQ(out, R"({"seq":7,"x":1.5,"y":-2})");
  ASSERT_TRUE(encode_v2_waypoint({18446744073709551615u, {0.1, 1e-7}}, {}, out).is_ok());
  EXPECT_EQ(out, R"({"seq":18446744073709551615,"x":0.1,"y":1e-07})");
  EXPECT_FALSE(nlohmann::json::parse(out).is_discarded());
}

TEST(EncodeV2Path, ExactText) {
  std::string out;
  const std::vector<Point> path = {{1.5, -2.0}, {3.0, 0.25}};
  ASSERT_TRUE(encode_v2_path(9, path, {}, out).is_ok());
  EXPECT_EQ(out, R"({"seq":9,"points":[[1.5,-2],[3,0.25]]})");
  ASSERT_TRUE(encode_v2_path(10, {}, {}, out).is_ok());
  EXPECT_EQ(out, R"({"seq":10,"points":[]})");
}

TEST(EncodeV2, RejectsUnsendableValuesAndEmptiesOutput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::string out = "stale";
  EXPECT_EQ(encode_v2_waypoint({1, {nan, 0.0}}, {}, out).reason(), RejectReason::NonFinite);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(encode_v2_waypoint({1, {0.0, -inf}}, {}, out).reason(), RejectReason::NonFinite);
  EXPECT_EQ(encode_v2_waypoint({1, {10000.01, 0.0}}, {}, out).reason(), RejectReason::OutOfRange);
  const std::vector<Point> bad = {{0.0, 0.0}, {0.0, nan}};
  out = "stale";
  const CodecStatus s = encode_v2_path(1, bad, {}, out);
  EXPECT_EQ(s.reason(), RejectReason::NonFinite);
  EXPECT_NE(s.detail().find("points[1]"), std::string::npos) << s.detail();
  EXPECT_TRUE(out.empty());
  CodecLimits few;
  few.max_points = 1;
  const std::vector<Point> two = {{0.0, 0.0}, {1.0, 1.0}};
  EXPECT_EQ(encode_v2_path(1, two, few, out).reason(), RejectReason::TooManyPoints);
}

TEST(V2ServerCodec, RoundTripIsExact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-9999.0, 9999.0);
  std::vector<Point> path(200);
  for (auto& p : path) p = {coord(rng), coord(rng)};
  std::string text;
  ASSERT_TRUE(encode_v2_path(42, path, {}, text).is_ok());
  V2Path decoded;
  ASSERT_TRUE(decode_v2_path(bytes(text), {}, decoded).is_ok());
  EXPECT_EQ(decoded.seq, 42u);
  EXPECT_EQ(decoded.points, path);  // bit-exact: shortest round-trip formatting

  const V2Waypoint waypoint{123456789, path[17]};
  ASSERT_TRUE(encode_v2_waypoint(waypoint, {}, text).is_ok());
  V2Waypoint back;
  ASSERT_TRUE(decode_v2_waypoint(bytes(text), {}, back).is_ok());
  EXPECT_EQ(back.seq, waypoint.seq);
  EXPECT_EQ(back.waypoint, waypoint.waypoint);
}

TEST(DecodeV2Waypoint, Rejections) {
  V2Waypoint out;
  const std::string cases[][3] = {
      {R"({"x": 1, "y": 2})", "missing_field", "seq is missing"},
      {R"({"seq": -1, "x": 1, "y": 2})", "json_type", "seq is number"},
      {R"({"seq": 1.5, "x": 1, "y": 2})", "json_type", "unsigned integer"},
      {R"({"seq": "1", "x": 1, "y": 2})", "json_type", "seq is string"},
      {R"({"seq": 1, "y": 2})", "missing_field", "x is missing"},
      {R"({"seq": 1, "x": 1, "y": 1e6})", "out_of_range", "y is 1000000"},
      {R"({"seq": 1, "x": 1, "y": 2)", "json_syntax", "byte"},
      {R"([1, 1, 2])", "json_type", "top level is array"},
  };
  for (const auto& c : cases) {
    const CodecStatus s = decode_v2_waypoint(bytes(c[0]), {}, out);
    ASSERT_FALSE(s.is_ok()) << c[0];
    EXPECT_EQ(reason_name(s.reason()), c[1]) << c[0] << " -> " << s.message();
    EXPECT_NE(s.detail().find(c[2]), std::string::npos) << c[0] << " -> " << s.message();
  }
}

TEST(DecodeV2Path, Rejections) {
  V2Path out;
  const std::string cases[][3] = {
      {R"({"seq": 1})", "missing_field", "points is missing"},
      {R"({"seq": 1, "points": [[1, 2], [1]]})", "json_type", "points[1]"},
      {R"({"seq": 1, "points": [[1, null]]})", "json_type", "points[0].y is null"},
      {R"({"seq": 1, "points": 5})", "json_type", "points is number"},
  };
  for (const auto& c : cases) {
    const CodecStatus s = decode_v2_path(bytes(c[0]), {}, out);
    ASSERT_FALSE(s.is_ok()) << c[0];
    EXPECT_EQ(reason_name(s.reason()), c[1]) << c[0] << " -> " << s.message();
    EXPECT_NE(s.detail().find(c[2]), std::string::npos) << c[0] << " -> " << s.message();
  }
  CodecLimits few;
  few.max_points = 1;
  EXPECT_EQ(decode_v2_path(bytes(R"({"seq": 1, "points": [[1, 2], [3, 4]]})"), few, out).reason(),
            RejectReason::TooManyPoints);
}

}  // namespace
}  // namespace slam::protocol

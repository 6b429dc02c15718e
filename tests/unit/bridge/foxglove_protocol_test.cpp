#include "bridge/core/foxglove_protocol.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace slam::bridge::foxglove {
namespace {

TEST(FoxgloveProtocol, FramesMessageDataLittleEndian) {
  const std::string frame = message_data(0x01020304, 0x1122334455667788ull, "{}");
  ASSERT_EQ(frame.size(), 15u);
  EXPECT_EQ(frame[0], 0x01);
  EXPECT_EQ(frame.substr(1, 4), std::string("\x04\x03\x02\x01", 4));
  EXPECT_EQ(frame.substr(5, 8), std::string("\x88\x77\x66\x55\x44\x33\x22\x11", 8));
  EXPECT_EQ(frame.substr(13), "{}");
}

TEST(FoxgloveProtocol, ParsesAClientMessage) {
  const std::string frame = std::string("\x01\x07\x00\x00\x00", 5) + R"({"a":1})";
  auto parsed = parse_client_binary(frame);
  ASSERT_TRUE(parsed) << parsed.message();
  const auto& m = std::get<ClientMessageData>(*parsed);
  EXPECT_EQ(m.channel_id, 7u);
  EXPECT_EQ(m.payload, R"({"a":1})");
}

TEST(FoxgloveProtocol, ParsesAServiceCallAndFramesItsResponse) {
  const std::string frame =
      std::string("\x02\x01\x00\x00\x00\x09\x00\x00\x00\x04\x00\x00\x00", 13) + "json{}";
  auto parsed = parse_client_binary(frame);
  ASSERT_TRUE(parsed) << parsed.message();
  const auto& r = std::get<ServiceCallRequest>(*parsed);
  EXPECT_EQ(r.service_id, 1u);
  EXPECT_EQ(r.call_id, 9u);
  EXPECT_EQ(r.encoding, "json");
  EXPECT_EQ(r.payload, "{}");
  EXPECT_EQ(service_call_response(1, 9, "json", "{}"), std::string("\x03", 1) + frame.substr(1));
}

TEST(FoxgloveProtocol, RefusesShortAndUnknownFrames) {
  EXPECT_FALSE(parse_client_binary(""));
  EXPECT_FALSE(parse_client_binary(std::string("\x01\x07\x00", 3)));
  EXPECT_FALSE(
      parse_client_binary(std::string("\x02\x01\x00\x00\x00\x09\x00\x00\x00\x40\x00\x00\x00json", 17)));
  EXPECT_FALSE(parse_client_binary("\x09"));
}

TEST(FoxgloveProtocol, AdvertisesChannelsWithTheirSchemas) {
  const auto j =
      nlohmann::json::parse(advertise({{3, "/robots", "json", "foxglove.SceneUpdate", "{}", "jsonschema"}}));
  EXPECT_EQ(j["op"], "advertise");
  EXPECT_EQ(j["channels"][0]["id"], 3);
  EXPECT_EQ(j["channels"][0]["schemaName"], "foxglove.SceneUpdate");
  EXPECT_EQ(j["channels"][0]["schemaEncoding"], "jsonschema");
}

}  // namespace
}  // namespace slam::bridge::foxglove

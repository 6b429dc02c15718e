// Hex dumps and parsing, v1 pair encoding (range-checked) and payload decoding for display.
#include "viewer/core/payload_text.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

TEST(PayloadText, HexRoundTrip) {
  const std::vector<uint8_t> b{0x00, 0x0a, 0xff};
  EXPECT_EQ(to_hex(b), "00 0a ff");
  auto parsed = parse_hex("00 0A, 0xff");
  ASSERT_TRUE(parsed) << parsed.message();
  EXPECT_EQ(*parsed, b);
  EXPECT_EQ(to_hex(b, 2), "00 0a ...(+1)");
}

TEST(PayloadText, HexErrorsNameTheProblem) {
  auto odd = parse_hex("abc");
  ASSERT_FALSE(odd);
  EXPECT_NE(odd.message().find("odd"), std::string::npos);
  auto bad = parse_hex("zz");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find("offset 0"), std::string::npos);
}

TEST(PayloadText, V1PairsEncodeLittleEndianAndRejectOutOfRange) {
  auto e = encode_v1_pairs({{1, -1}, {300, 0}});
  ASSERT_TRUE(e);
  EXPECT_EQ(*e, (std::vector<uint8_t>{0x01, 0x00, 0xff, 0xff, 0x2c, 0x01, 0x00, 0x00}));
  auto big = encode_v1_pairs({{40000, 0}});
  ASSERT_FALSE(big);
  EXPECT_NE(big.message().find("40000"), std::string::npos);
  EXPECT_FALSE(encode_v1_pairs({}));
}

TEST(PayloadText, ParsesPairs) {
  auto p = parse_pairs("(10, 20) 30,-40");
  ASSERT_TRUE(p) << p.message();
  ASSERT_EQ(p->size(), 2u);
  EXPECT_EQ((*p)[1].second, -40);
  EXPECT_FALSE(parse_pairs("1 2 3"));
  EXPECT_FALSE(parse_pairs("1 x"));
}

TEST(PayloadText, DecodesV1AndText) {
  auto adv = encode_v1_pairs({{100, 200}, {-5, 7}});
  ASSERT_TRUE(adv);
  EXPECT_EQ(decode_payload("v1/robot/r1/adv", *adv), "pos (100, 200); 1 obstacles: (-5, 7)");
  auto cmd = encode_v1_pairs({{3, 4}});
  EXPECT_EQ(decode_payload("v1/server/r1/cmd", *cmd), "waypoint (3, 4)");
  const std::string json = R"({"x": 1})";
  EXPECT_EQ(decode_payload("v2/robot/r1/pose", std::vector<uint8_t>(json.begin(), json.end())), json);
  EXPECT_EQ(decode_payload("other", std::vector<uint8_t>{0x00, 0xc3}), "00 c3");
}

}  // namespace
}  // namespace slam::viewer

#include "bridge/core/base64.hpp"

#include <gtest/gtest.h>

#include <string_view>

namespace slam::bridge {
namespace {

std::string encode(std::string_view text) {
  return base64({reinterpret_cast<const uint8_t*>(text.data()), text.size()});
}

TEST(Base64, EncodesTheRfc4648Vectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, EncodesHighBytes) {
  const uint8_t bytes[] = {0xff, 0xfe, 0x00};
  EXPECT_EQ(base64(bytes), "//4A");
}

}  // namespace
}  // namespace slam::bridge

// bounded_prefix: text fits a bounded IDL string without splitting a UTF-8 character.
#include "common/core/bounded_text.hpp"

#include <gtest/gtest.h>

namespace slam {
namespace {

TEST(BoundedPrefix, KeepsShortTextAndCutsLongTextAtACharacterBoundary) {
  EXPECT_EQ(bounded_prefix("robot", 64), "robot");
  EXPECT_EQ(bounded_prefix("robot", 5), "robot");
  EXPECT_EQ(bounded_prefix("robot", 3), "rob");
  EXPECT_EQ(bounded_prefix("", 0), "");
  const std::string_view accented = "ab\xc3\xa9";  // "abé": é is two bytes
  EXPECT_EQ(bounded_prefix(accented, 3), "ab");    // not half of é
  EXPECT_EQ(bounded_prefix(accented, 4), accented);
  const std::string_view emoji = "\xf0\x9f\xa4\x96!";  // a four-byte character
  EXPECT_EQ(bounded_prefix(emoji, 3), "");
  EXPECT_EQ(bounded_prefix(emoji, 4), "\xf0\x9f\xa4\x96");
}

}  // namespace
}  // namespace slam

// UTF-8 well-formedness and control characters, against the Unicode table's edge cases.
#include "protocol/text_check.hpp"

#include <gtest/gtest.h>

#include <string>

namespace slam::protocol {
namespace {

TEST(TextCheck, AcceptsCleanText) {
  for (const std::string s :
       {"", "robot-1", "Łódź", "ロボット", "\xF0\x9F\xA4\x96", "\xF4\x8F\xBF\xBF", "a b"})
    EXPECT_FALSE(find_text_problem(s).has_value()) << s;
}

TEST(TextCheck, RejectsIllFormedUtf8WithOffset) {
  struct Case {
    std::string text;
    std::size_t offset;
  };
  for (const Case& c : {Case{"ab\xFF", 2}, Case{"\xC0\xAF", 0},  // overlong '/'
                        Case{"\xE0\x80\xAF", 0},                 // overlong 3-byte
                        Case{"x\xED\xA0\x80", 1},                // surrogate U+D800
                        Case{"\xF4\x90\x80\x80", 0},             // above U+10FFFF
                        Case{"\xF0\x8F\xBF\xBF", 0},             // overlong 4-byte
                        Case{"ok\xE2\x82", 2},                   // truncated
                        Case{"\x80", 0}, Case{"\xF5\x80\x80\x80", 0}}) {
    const auto problem = find_text_problem(c.text);
    ASSERT_TRUE(problem.has_value()) << c.text;
    EXPECT_EQ(problem->what, "invalid UTF-8");
    EXPECT_EQ(problem->offset, c.offset);
  }
}

TEST(TextCheck, RejectsControlCharacters) {
  for (const std::string& s : {std::string("a\0b", 3), std::string("tab\there"), std::string("new\nline"),
                               std::string("del\x7F"), std::string("c1\xC2\x85")}) {
    const auto problem = find_text_problem(s);
    ASSERT_TRUE(problem.has_value()) << s;
    EXPECT_EQ(problem->what, "control character");
  }
  EXPECT_FALSE(find_text_problem("\xC2\xA0").has_value());  // U+00A0 is not a control
}

TEST(EscapeForLog, KeepsPrintableAsciiAndHexesTheRest) {
  EXPECT_EQ(escape_for_log("robot-1"), "robot-1");
  EXPECT_EQ(escape_for_log("a\nb\xFF\\"), "a\\x0ab\\xff\\x5c");
  EXPECT_EQ(escape_for_log(std::string(200, 'x'), 4), "xxxx...");
}

}  // namespace
}  // namespace slam::protocol

#include "common/core/result.hpp"

#include <gtest/gtest.h>

namespace slam {
namespace {

Status fails(const char* why) {
  return Error{why};
}
Status succeeds() {
  return {};
}
Result<int> number(bool ok) {
  if (!ok) return Error{"no number"};
  return 7;
}

Status try_status(bool ok) {
  SLAM_TRY(ok ? succeeds() : fails("first step failed"));
  return {};
}

Result<std::string> try_result_from_other_result(bool ok) {
  SLAM_TRY(number(ok));
  return std::string("done");
}

Result<double> propagate_with_error(bool ok) {
  auto n = number(ok);
  if (!n) return n.error();
  return *n * 0.5;
}

TEST(Result, TryReturnsTheFailureOfAStatus) {
  EXPECT_TRUE(try_status(true).is_ok());
  const Status s = try_status(false);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "first step failed");
}

TEST(Result, TryReturnsTheFailureOfAResultOfAnotherType) {
  EXPECT_EQ(*try_result_from_other_result(true), "done");
  const auto r = try_result_from_other_result(false);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), "no number");
}

TEST(Result, ErrorCarriesTheMessageAcrossTypes) {
  EXPECT_DOUBLE_EQ(*propagate_with_error(true), 3.5);
  const auto r = propagate_with_error(false);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), "no number");
  EXPECT_EQ(fails("x").error().message, "x");
}

TEST(Result, StatusOfAResultKeepsTheMessage) {
  EXPECT_TRUE(number(true).status().is_ok());
  EXPECT_EQ(number(false).status().message(), "no number");
}

}  // namespace
}  // namespace slam

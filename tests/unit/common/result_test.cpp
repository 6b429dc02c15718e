#include "common/core/result.hpp"

#include <gtest/gtest.h>

#include <cstdint>

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

enum class SampleError : uint16_t { Busy = 1, Gone };
constexpr ErrorDomain error_domain(SampleError) {
  return ErrorDomain::Map;
}

Result<int> coded(bool ok) {
  if (!ok) return Error{"the service is busy", SampleError::Busy};
  return 1;
}

Status coded_through_try(bool ok) {
  SLAM_TRY(coded(ok));
  return {};
}

TEST(Result, AnErrorsCodeSaysItsCauseWithoutTheText) {
  const auto r = coded(false);
  EXPECT_TRUE(r.is(SampleError::Busy));
  EXPECT_FALSE(r.is(SampleError::Gone));
  EXPECT_EQ(r.code(), ErrorCode(SampleError::Busy));
  EXPECT_EQ(r.code().domain(), ErrorDomain::Map);
  EXPECT_FALSE(coded(true).is(SampleError::Busy));
  EXPECT_EQ(coded(true).code(), ErrorCode{});
}

TEST(Result, TheCodeTravelsWithTheFailure) {
  const Status s = coded_through_try(false);
  EXPECT_TRUE(s.is(SampleError::Busy));
  EXPECT_EQ(s.message(), "the service is busy");
  EXPECT_TRUE(coded(false).status().is(SampleError::Busy));
  EXPECT_TRUE(s.error().is(SampleError::Busy));
  EXPECT_FALSE(coded_through_try(true).is(SampleError::Busy));
}

TEST(Result, AFailureSaidOnlyInWordsHasNoCode) {
  EXPECT_EQ(fails("x").code(), ErrorCode{});
  EXPECT_FALSE(fails("x").is(SampleError::Busy));
}

}  // namespace
}  // namespace slam

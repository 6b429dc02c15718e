// Reason names are an operator-facing contract (counter names): pin every one.
#include "protocol/reject_reason.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace slam::protocol {
namespace {

TEST(RejectReason, NamesAreStableSnakeCase) {
  EXPECT_EQ(reason_name(RejectReason::EmptyPayload), "empty_payload");
  EXPECT_EQ(reason_name(RejectReason::Oversized), "oversized");
  EXPECT_EQ(reason_name(RejectReason::BadLength), "bad_length");
  EXPECT_EQ(reason_name(RejectReason::TooManyPoints), "too_many_points");
  EXPECT_EQ(reason_name(RejectReason::UnknownTopic), "unknown_topic");
  EXPECT_EQ(reason_name(RejectReason::BadRobotId), "bad_robot_id");
  EXPECT_EQ(reason_name(RejectReason::JsonSyntax), "json_syntax");
  EXPECT_EQ(reason_name(RejectReason::JsonType), "json_type");
  EXPECT_EQ(reason_name(RejectReason::MissingField), "missing_field");
  EXPECT_EQ(reason_name(RejectReason::NonFinite), "non_finite");
  EXPECT_EQ(reason_name(RejectReason::OutOfRange), "out_of_range");
  EXPECT_EQ(reason_name(RejectReason::BadText), "bad_text");
  EXPECT_EQ(reason_name(RejectReason::BadVersion), "bad_version");
  EXPECT_EQ(reason_name(RejectReason::UnknownRobot), "unknown_robot");
}

TEST(RejectReason, EveryReasonHasACounterAndDescription) {
  std::set<std::string> counters;
  for (const RejectReason r : kAllRejectReasons) {
    EXPECT_EQ(reason_counter(r), "rejected_" + std::string(reason_name(r)));
    EXPECT_FALSE(reason_description(r).empty());
    counters.emplace(reason_counter(r));
  }
  EXPECT_EQ(counters.size(), kRejectReasonCount);
}

TEST(CodecStatus, OkAndRejected) {
  const CodecStatus ok = CodecStatus::ok();
  EXPECT_TRUE(ok.is_ok());
  EXPECT_TRUE(static_cast<bool>(ok));
  EXPECT_EQ(ok.message(), "ok");

  const CodecStatus bad{RejectReason::BadLength, "payload is 7 bytes, not a multiple of 4"};
  EXPECT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.reason(), RejectReason::BadLength);
  EXPECT_EQ(bad.message(), "bad_length: payload is 7 bytes, not a multiple of 4");
}

TEST(CodecStatus, EmptyDetailFallsBackToDescription) {
  const CodecStatus bad{RejectReason::EmptyPayload, ""};
  EXPECT_EQ(bad.message(), "empty_payload: payload is empty");
}

}  // namespace
}  // namespace slam::protocol

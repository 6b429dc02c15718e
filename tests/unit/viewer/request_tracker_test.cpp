// RequestTracker: the last request's reply matched by id, and "no reply" after the timeout.
#include "viewer/core/request_tracker.hpp"

#include <gtest/gtest.h>

#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

TEST(RequestTracker, NothingSentShowsNothing) {
  RequestTracker t;
  t.tick(100 * kSecond);
  EXPECT_FALSE(t.last());
  EXPECT_FALSE(t.reply(1, true, ""));
}

TEST(RequestTracker, SentRequestWaits) {
  RequestTracker t(3 * kSecond);
  t.sent(7, "pause", 10 * kSecond);
  ASSERT_TRUE(t.last());
  EXPECT_EQ(t.last()->state, RequestState::Waiting);
  EXPECT_EQ(describe(*t.last()), "#7 pause: waiting for the reply");
}

TEST(RequestTracker, MatchingOkReplyShowsOk) {
  RequestTracker t;
  t.sent(7, "pause", 0);
  EXPECT_TRUE(t.reply(7, true, ""));
  EXPECT_EQ(t.last()->state, RequestState::Ok);
  EXPECT_EQ(describe(*t.last()), "#7 pause: ok");
}

TEST(RequestTracker, FailedReplyShowsTheServiceMessage) {
  RequestTracker t;
  t.sent(8, "remove r9", 0);
  EXPECT_TRUE(t.reply(8, false, "no simulated robot 'r9'"));
  EXPECT_EQ(t.last()->state, RequestState::Failed);
  EXPECT_EQ(describe(*t.last()), "#8 remove r9: failed: no simulated robot 'r9'");
}

TEST(RequestTracker, ReplyToAnotherRequestIsIgnored) {
  RequestTracker t;
  t.sent(8, "pause", 0);
  EXPECT_FALSE(t.reply(9, false, "someone else's"));
  EXPECT_FALSE(t.reply(0, false, "no id"));
  EXPECT_EQ(t.last()->state, RequestState::Waiting);
}

TEST(RequestTracker, ReplyToAnOlderRequestDoesNotChangeTheLast) {
  RequestTracker t;
  t.sent(1, "spawn 1 robot", 0);
  t.sent(2, "pause", 0);
  EXPECT_FALSE(t.reply(1, true, ""));
  EXPECT_EQ(t.last()->id, 2u);
  EXPECT_EQ(t.last()->state, RequestState::Waiting);
}

TEST(RequestTracker, NoReplyAfterTheTimeout) {
  RequestTracker t(3 * kSecond);
  t.sent(5, "resume", 10 * kSecond);
  t.tick(13 * kSecond);  // exactly the timeout: still waiting
  EXPECT_EQ(t.last()->state, RequestState::Waiting);
  t.tick(13 * kSecond + 1);
  EXPECT_EQ(t.last()->state, RequestState::NoReply);
  EXPECT_EQ(describe(*t.last()), "#5 resume: no reply");
}

TEST(RequestTracker, TimeoutLeavesAnAnsweredRequestAlone) {
  RequestTracker t(3 * kSecond);
  t.sent(5, "resume", 0);
  EXPECT_TRUE(t.reply(5, false, "bad"));
  t.tick(100 * kSecond);
  EXPECT_EQ(t.last()->state, RequestState::Failed);
}

TEST(RequestTracker, LateReplyReplacesNoReply) {
  RequestTracker t(3 * kSecond);
  t.sent(5, "resume", 0);
  t.tick(4 * kSecond);
  ASSERT_EQ(t.last()->state, RequestState::NoReply);
  EXPECT_TRUE(t.reply(5, true, ""));
  EXPECT_EQ(t.last()->state, RequestState::Ok);
}

TEST(RequestTracker, NewRequestWaitsAgain) {
  RequestTracker t(3 * kSecond);
  t.sent(5, "resume", 0);
  t.tick(4 * kSecond);
  t.sent(6, "pause", 4 * kSecond);
  EXPECT_EQ(t.last()->state, RequestState::Waiting);
  t.tick(6 * kSecond);
  EXPECT_EQ(t.last()->state, RequestState::Waiting);
}

// ViewerState::ingest routes each service's replies to its own tracker and ticks both.
TEST(RequestTracker, IngestMatchesGatewayAndSimulatorReplies) {
  ViewerState state(100);
  state.mqtt_requests.sent(11, "subscribe a/#", 0);
  state.sim_requests.sent(11, "pause", 0);  // the same id on the other topic must not match
  IntakeBatch batch;
  batch.mqtt_replies.push_back({{11, false, "not connected"}});
  state.ingest(batch, kSecond);
  EXPECT_EQ(state.mqtt_requests.last()->state, RequestState::Failed);
  EXPECT_EQ(state.mqtt_requests.last()->message, "not connected");
  EXPECT_EQ(state.sim_requests.last()->state, RequestState::Waiting);

  batch.clear();
  batch.sim_replies.push_back({{11, true, ""}});
  state.ingest(batch, 2 * kSecond);
  EXPECT_EQ(state.sim_requests.last()->state, RequestState::Ok);
}

TEST(RequestTracker, IngestDeclaresSilentRequestsUnanswered) {
  ViewerState state(100);
  state.sim_requests.sent(3, "pause", 0);
  IntakeBatch empty;
  state.ingest(empty, kReplyTimeoutNs + 1);
  EXPECT_EQ(state.sim_requests.last()->state, RequestState::NoReply);
}

}  // namespace
}  // namespace slam::viewer

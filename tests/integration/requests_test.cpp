// Requests that cannot be lost, and one mapper per domain, against real processes: a request whose
// first copy goes nowhere (slamctl starts before the mapper, with no wait for a match) is still
// answered, and executed once; a repeated request id is answered again without a second execution;
// of two mappers started together exactly one stays, and a later one refuses too.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

using namespace std::chrono_literals;

// The value of `name` in the latest heartbeat of `service` (-1 when none carries it).
int64_t counter(const Inbox<Heartbeat>& beats, const std::string& service, const std::string& name) {
  int64_t value = -1;
  for (const Heartbeat& h : beats.items()) {
    if (h.service() != service) continue;
    for (const Counter& c : h.counters())
      if (c.name() == name) value = c.value();
  }
  return value;
}

class RequestsTest : public ::testing::Test {
 protected:
  RequestsTest() {
    auto p = dds::Participant::create(domain.id(), "requests-test");
    if (!p) throw std::runtime_error(p.message());
    participant = std::move(*p);
    heartbeat_reader = make_inbox_reader(*participant, dds::kHeartbeat, beats);
    reply_reader = make_inbox_reader(*participant, dds::kMapReply, replies);
  }
  void TearDown() override {
    if (HasFailure())
      for (const char* s : {"mapper", "slamctl"}) std::cerr << s << " log:\n" << group.log(s) << "\n";
  }
  void start_mapper(const std::string& name = "mapper") {
    group.start(name, {bin_path("slam-mapper"), "--domain", std::to_string(domain.id()), "--store",
                       group.dir() + "/" + name + ".db", "--slam", "off"});
  }
  std::vector<MapReply> replies_to(uint64_t id) const {
    std::vector<MapReply> out;
    for (const MapReply& r : replies.items())
      if (r.request_id() == id) out.push_back(r);
    return out;
  }

  DomainLease domain;
  ProcessGroup group;
  std::unique_ptr<dds::Participant> participant;
  Inbox<Heartbeat> beats;
  Inbox<MapReply> replies;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
  std::unique_ptr<dds::Reader<MapReply>> reply_reader;
};

TEST_F(RequestsTest, RequestSentBeforeTheMapperExistsIsAnsweredAndExecutedOnce) {
  // slamctl first: its first copy of the edit has no reader anywhere and is lost.
  group.start("slamctl", {bin_path("slamctl"), "--domain", std::to_string(domain.id()), "--timeout", "60",
                          "obstruct", "3", "3"});
  start_mapper();
  ASSERT_EQ(group.wait_exit("slamctl", 90s), 0) << group.log("slamctl");
  EXPECT_NE(group.log("slamctl").find("obstructed the cell"), std::string::npos) << group.log("slamctl");
  EXPECT_EQ(group.log("slamctl").find("already"), std::string::npos) << group.log("slamctl");
  ASSERT_TRUE(wait_until([&] { return counter(beats, "mapper", "requests_executed") >= 1; }, 30s));
  EXPECT_EQ(counter(beats, "mapper", "requests_executed"), 1);
}

TEST_F(RequestsTest, RepeatedIdIsAnsweredFromTheCacheWithoutExecutingTwice) {
  start_mapper();
  auto edits = make_test_writer(*participant, dds::kMapEdit);
  auto requester = make_test_requester(*participant, dds::kMapReply, 60s);
  MapEdit edit;
  edit.kind(EDIT_OBSTRUCT);
  edit.point().x(2.0);
  edit.point().y(2.0);
  const auto first = requester->call(*edits, edit);
  ASSERT_TRUE(first) << "no reply to the first copy";
  ASSERT_EQ(first->result(), MAP_OK) << first->message();

  // The same id again, as a retry whose reply was lost would arrive: executing it again would
  // answer "already obstructed".
  edit.request_id(first->request_id());
  ASSERT_TRUE(edits->write(edit));
  ASSERT_TRUE(wait_until([&] { return replies_to(first->request_id()).size() >= 2; }, 30s));
  for (const MapReply& r : replies_to(first->request_id())) {
    EXPECT_EQ(r.result(), MAP_OK);
    EXPECT_EQ(r.message(), first->message());
  }
  ASSERT_TRUE(wait_until([&] { return counter(beats, "mapper", "requests_repeated") >= 1; }, 30s));
  EXPECT_EQ(counter(beats, "mapper", "requests_executed"), 1);
}

// Two mappers on one domain: exactly one keeps running, the other exits non-zero with one line that
// names the first; a third started later refuses as well; only one mapper publishes the map.
TEST_F(RequestsTest, SecondMapperOnTheDomainRefuses) {
  Inbox<GridSnapshot> snapshots;
  auto snapshot_reader = make_inbox_reader(*participant, dds::kGridSnapshot, snapshots);
  start_mapper("mapper-a");
  start_mapper("mapper-b");
  ASSERT_TRUE(wait_until([&] { return !group.running("mapper-a") || !group.running("mapper-b"); }, 60s))
      << "both mappers still run";
  const bool a_left = !group.running("mapper-a");
  const std::string loser = a_left ? "mapper-a" : "mapper-b";
  const std::string winner = a_left ? "mapper-b" : "mapper-a";
  EXPECT_EQ(group.wait_exit(loser, 10s), 1) << group.log(loser);
  EXPECT_NE(group.log(loser).find("error: another mapper"), std::string::npos) << group.log(loser);
  EXPECT_NE(group.log(loser).find("pid " + std::to_string(group.pid(winner))), std::string::npos)
      << group.log(loser);

  ASSERT_TRUE(wait_until([&] { return snapshots.size() > 0; }, 60s)) << group.log(winner);
  start_mapper("mapper-c");
  EXPECT_EQ(group.wait_exit("mapper-c", 60s), 1) << group.log("mapper-c");
  EXPECT_NE(group.log("mapper-c").find("another mapper runs"), std::string::npos) << group.log("mapper-c");
  EXPECT_TRUE(group.running(winner)) << group.log(winner);
  EXPECT_EQ(snapshot_reader->matched_writers(), 1);
}

}  // namespace
}  // namespace slam::testkit

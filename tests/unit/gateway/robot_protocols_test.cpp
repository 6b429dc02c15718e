// RobotProtocols: the owner of a robot answers in the protocol of the freshest report, whichever
// gateway received the robot's messages.
#include "gateway/core/robot_protocols.hpp"

#include <gtest/gtest.h>

namespace slam::gateway {
namespace {

TEST(RobotProtocols, KeepsTheFreshestReport) {
  RobotProtocols book(10);
  EXPECT_TRUE(book.learn("r1", {Protocol::V1, 100}));
  EXPECT_TRUE(book.learn("r1", {Protocol::V2, 50}));  // older: ignored
  EXPECT_EQ(book.find("r1")->protocol, Protocol::V1);
  EXPECT_TRUE(book.learn("r1", {Protocol::V2, 200}));
  EXPECT_EQ(book.find("r1")->protocol, Protocol::V2);
  EXPECT_FALSE(book.find("r2"));
}

TEST(RobotProtocols, StaysBounded) {
  RobotProtocols book(2);
  EXPECT_TRUE(book.learn("a", {Protocol::V1, 1}));
  EXPECT_TRUE(book.learn("b", {Protocol::V1, 1}));
  EXPECT_FALSE(book.learn("c", {Protocol::V1, 1}));
  EXPECT_TRUE(book.learn("a", {Protocol::V2, 2}));  // a known robot still updates
  EXPECT_EQ(book.size(), 2u);
}

TEST(RobotProtocols, FresherPicksTheLaterReportOrTheOnlyOne) {
  const LearntProtocol local{Protocol::V1, 100};
  const LearntProtocol peer{Protocol::V2, 150};
  EXPECT_EQ(fresher(local, peer)->protocol, Protocol::V2);
  EXPECT_EQ(fresher(peer, local)->protocol, Protocol::V2);
  EXPECT_EQ(fresher(local, std::nullopt)->protocol, Protocol::V1);
  EXPECT_EQ(fresher(std::nullopt, peer)->protocol, Protocol::V2);
  EXPECT_FALSE(fresher(std::nullopt, std::nullopt));
}

}  // namespace
}  // namespace slam::gateway

// MQTT log bounding: by entry count and by bytes, oldest evicted first, counts kept.
#include "viewer/core/mqtt_log.hpp"

#include <gtest/gtest.h>

namespace slam::viewer {
namespace {

MqttEntry entry(uint64_t seq, size_t payload, bool inbound = true) {
  return {
      seq, 0, inbound, "v1/robot/r/adv", std::vector<uint8_t>(payload, 0xab), static_cast<uint32_t>(payload)};
}

TEST(MqttLog, BoundedByEntries) {
  MqttLog log(3, size_t{1} << 30);
  for (uint64_t i = 0; i < 10; ++i) log.push(entry(i, 4));
  EXPECT_EQ(log.size(), 3u);
  EXPECT_EQ(log.at(0).seq, 7u);
  EXPECT_EQ(log.at(2).seq, 9u);
  EXPECT_EQ(log.evicted(), 7u);
  EXPECT_EQ(log.inbound(), 10u);
}

TEST(MqttLog, BoundedByBytes) {
  const size_t one = MqttLog::cost(entry(0, 1000));
  MqttLog log(1000, one * 5 + 10);
  for (uint64_t i = 0; i < 50; ++i) log.push(entry(i, 1000, i % 2 == 0));
  EXPECT_EQ(log.size(), 5u);
  EXPECT_LE(log.bytes(), log.max_bytes());
  EXPECT_EQ(log.at(4).seq, 49u);
  EXPECT_EQ(log.inbound(), 25u);
  EXPECT_EQ(log.outbound(), 25u);
}

TEST(MqttLog, OversizedEntryDoesNotStay) {
  MqttLog log(10, 100);
  log.push(entry(1, 1000));
  EXPECT_EQ(log.size(), 0u);
  EXPECT_EQ(log.bytes(), 0u);
  EXPECT_EQ(log.evicted(), 1u);
}

TEST(MqttLog, ClearEmptiesButKeepsTotals) {
  MqttLog log;
  log.push(entry(1, 10));
  log.clear();
  EXPECT_EQ(log.size(), 0u);
  EXPECT_EQ(log.bytes(), 0u);
  EXPECT_EQ(log.inbound(), 1u);
}

}  // namespace
}  // namespace slam::viewer

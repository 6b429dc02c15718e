// slam-simulator's range noise, seen from the broker: without noise every reported obstacle point
// lies on a true wall; after SimControl SIM_SET_NOISE the ranges scatter around the true ones with
// about the requested standard deviation. Every SimControl command gets a SimReply by its id, and a
// command that cannot be applied is answered ok=false with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"
#include "protocol/v1_codec.hpp"
#include "simulator/core/builtin_worlds.hpp"

namespace slam::testkit {
namespace {

constexpr double kMaxRange = 30.0;
constexpr uint64_t kHandshakeId = 1000;  // beyond the 10 m world's diagonal: every beam hits a wall

// Reported minus true range of every obstacle point in the v1 adv messages: the beam's direction is
// taken from the robot's reported position to the point, the true range cast in the true world.
std::vector<double> range_errors(const std::vector<MqttMessage>& messages, const sim::World& world) {
  std::vector<double> errors;
  for (const MqttMessage& m : messages) {
    protocol::DecodedObservation obs;
    const auto* data = reinterpret_cast<const uint8_t*>(m.payload.data());
    if (!protocol::decode_v1({data, m.payload.size()}, {}, obs).is_ok()) {
      ADD_FAILURE() << "undecodable adv on " << m.topic;
      continue;
    }
    for (const protocol::Point& p : obs.hits) {
      const double dx = p.x - obs.x;
      const double dy = p.y - obs.y;
      const double reported = std::hypot(dx, dy);
      if (reported < 1e-6) continue;
      const double truth = world.cast({obs.x, obs.y}, {dx / reported, dy / reported}, kMaxRange);
      errors.push_back(reported - truth);
    }
  }
  return errors;
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

double standard_deviation(const std::vector<double>& v) {
  const double m = mean(v);
  double sum = 0.0;
  for (double x : v) sum += (x - m) * (x - m);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

class SimulatorRangeNoiseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    group.start("simulator",
                {bin_path("slam-simulator"), "--domain", std::to_string(domain.id()), "--broker",
                 "tcp://127.0.0.1:" + std::to_string(port), "--world", "empty", "--seed", "11", "--robots",
                 "1", "--noise", "0", "--drift", "0", "--max-range", std::to_string(kMaxRange)});
    auto p = dds::Participant::create(domain.id(), "sim-noise-test");
    ASSERT_TRUE(p) << p.message();
    participant = std::move(*p);
    controls = make_test_writer(*participant, dds::kSimControl);
    reply_reader = make_inbox_reader(*participant, dds::kSimReply, replies);
    ASSERT_TRUE(controls->wait_for_readers(20s)) << group.log("simulator");
    ASSERT_TRUE(reply_reader->wait_for_writers(20s)) << group.log("simulator");
    ASSERT_EQ(mqtt.connect(), 0);
    ASSERT_TRUE(mqtt.subscribe("v1/robot/+/adv"));
    // Matching is not symmetric at once: resend a harmless command until the simulator answers it,
    // so the test's own commands are not written before the simulator's reader knows this writer.
    SimControl resume;
    resume.command_id(kHandshakeId);
    resume.kind(SIM_RESUME);
    ASSERT_TRUE(wait_until(
        [&] {
          controls->write(resume);
          return reply(kHandshakeId, 300ms).has_value();
        },
        20s))
        << group.log("simulator");
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "simulator log:\n" << group.log("simulator") << "\n";
  }

  std::optional<SimReply> reply(uint64_t id, std::chrono::milliseconds timeout = 10s) const {
    return replies.wait_for([id](const SimReply& r) { return r.command_id() == id; }, timeout);
  }
  // The `messages` advs that arrive after the next `skip` ones.
  std::vector<MqttMessage> collect(size_t skip, size_t messages) {
    const size_t from = mqtt.messages().size() + skip;
    EXPECT_TRUE(wait_until([&] { return mqtt.messages().size() >= from + messages; }, 30s));
    const auto all = mqtt.messages();
    return {all.begin() + static_cast<std::ptrdiff_t>(std::min(from, all.size())), all.end()};
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  MqttTestClient mqtt{port, "sim-noise-test"};
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Writer<SimControl>> controls;
  Inbox<SimReply> replies;
  std::unique_ptr<dds::Reader<SimReply>> reply_reader;
};

TEST_F(SimulatorRangeNoiseTest, PointsLieOnTheWallsWithoutNoiseAndScatterWithTheRequestedSd) {
  const auto world = sim::builtin_world("empty");
  ASSERT_TRUE(world) << world.message();

  // No noise: only v1's centimetre rounding of robot and point.
  const auto exact = range_errors(collect(0, 20), *world);
  ASSERT_GT(exact.size(), 100u);
  for (double e : exact) EXPECT_LT(std::abs(e), 0.02) << "range error " << e << " m without noise";

  constexpr double kSd = 0.1;
  SimControl noise;
  noise.command_id(1);
  noise.kind(SIM_SET_NOISE);
  noise.range_noise_sd(kSd);
  controls->write(noise);
  const auto applied = reply(1);
  ASSERT_TRUE(applied) << "no SimReply to SIM_SET_NOISE";
  ASSERT_TRUE(applied->ok()) << applied->message().to_string();

  // Skip advs that may have been scanned before the command was applied.
  const auto noisy = range_errors(collect(3, 40), *world);
  ASSERT_GT(noisy.size(), 300u);
  // With n > 300 the sample sd is within a few percent of the true one; the bounds leave room for
  // rounding and are still far from 0 (no noise) and 2 x sd.
  EXPECT_NEAR(standard_deviation(noisy), kSd, 0.3 * kSd);
  EXPECT_NEAR(mean(noisy), 0.0, 0.03);
}

TEST_F(SimulatorRangeNoiseTest, EveryCommandIsAnsweredAndInvalidOnesSayWhy) {
  SimControl negative_noise;
  negative_noise.command_id(21);
  negative_noise.kind(SIM_SET_NOISE);
  negative_noise.range_noise_sd(-0.5);
  SimControl unknown_robot;
  unknown_robot.command_id(22);
  unknown_robot.kind(SIM_REMOVE);
  unknown_robot.robot_id("nobody");
  SimControl missing_world;
  missing_world.command_id(23);
  missing_world.kind(SIM_SET_WORLD);
  missing_world.world("no-such-world-file.txt");
  SimControl pause;
  pause.command_id(24);
  pause.kind(SIM_PAUSE);
  for (const SimControl* c : {&negative_noise, &unknown_robot, &missing_world, &pause}) controls->write(*c);

  const std::map<uint64_t, std::string> refused = {
      {21, "range_noise_sd"}, {22, "nobody"}, {23, "no-such-world-file.txt"}};
  for (const auto& [id, why] : refused) {
    const auto r = reply(id);
    ASSERT_TRUE(r) << "no SimReply to command " << id;
    EXPECT_FALSE(r->ok()) << "command " << id;
    EXPECT_NE(r->message().to_string().find(why), std::string::npos)
        << "command " << id << ": " << r->message().to_string();
  }
  const auto paused = reply(24);
  ASSERT_TRUE(paused) << "no SimReply to command 24";
  EXPECT_TRUE(paused->ok()) << paused->message().to_string();
  EXPECT_EQ(paused->message().to_string(), "");
}

}  // namespace
}  // namespace slam::testkit

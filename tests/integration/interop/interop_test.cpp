// Vendor interop, every IDL topic type, both directions: this process writes a sample with Fast DDS;
// interop_cyclone_echo (a separate process) reads it with Cyclone DDS into its C struct and writes
// that struct back with Cyclone; this process reads the echo with Fast DDS and compares every field
// (generated operator==) with what it sent. Real topic names and QoS from topics.hpp.
#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "interop_topics.hpp"
#include "process_group.hpp"
#include "samples.hpp"

namespace slam::interop {
namespace {

using namespace std::chrono_literals;

class InteropEnvironment {
 public:
  static InteropEnvironment& get() {
    static InteropEnvironment env;
    return env;
  }
  dds::Participant& participant() { return *participant_; }
  testkit::ProcessGroup& group() { return *group_; }

 private:
  InteropEnvironment() {
    group_ = std::make_unique<testkit::ProcessGroup>();
    group_->start("cyclone_echo", {testkit::bin_path("interop_cyclone_echo"), std::to_string(domain_.id())});
    auto p = dds::Participant::create(domain_.id(), "interop_test");
    if (!p) throw std::runtime_error(p.message());
    participant_ = std::move(*p);
  }
  testkit::DomainLease domain_;
  std::unique_ptr<testkit::ProcessGroup> group_;
  std::unique_ptr<dds::Participant> participant_;
};

struct Case {
  std::string type;
  std::function<void()> run;
};

// Sends `sample` on `topic` until its echo arrives (discovery may need a moment), then compares.
template <class T, class P>
void round_trip(const dds::Topic<T, P>& topic, const T& sample) {
  auto& env = InteropEnvironment::get();
  static std::string echo;  // one name per instantiation; Topic keeps a const char*
  echo = echo_name(topic.info.name);
  const dds::Topic<T, P> echo_topic{{echo.c_str(), topic.info.qos}};
  auto writer = dds::make_writer(env.participant(), topic);
  ASSERT_TRUE(writer) << writer.message();
  auto reader = dds::make_reader(env.participant(), echo_topic);
  ASSERT_TRUE(reader) << reader.message();
  ASSERT_TRUE(testkit::wait_until(
      [&] { return (*writer)->matched_readers() > 0 && (*reader)->matched_writers() > 0; }, 20s))
      << "Cyclone echo never matched " << topic.info.name
      << " (readers of ours: " << (*writer)->matched_readers()
      << ", writers of the echo: " << (*reader)->matched_writers() << ")";

  std::vector<T> got;
  const bool echoed = testkit::wait_until(
      [&] {
        (*writer)->write(sample);
        return testkit::wait_until([&] { return (*reader)->take(got) > 0; }, 300ms);
      },
      20s, 1ms);
  ASSERT_TRUE(echoed) << "no echo on " << echo << "\n" << env.group().log("cyclone_echo");
  EXPECT_TRUE(got.front() == sample) << "the sample on " << topic.info.name
                                     << " changed crossing Fast DDS -> Cyclone -> Fast DDS";
}

template <class T, class P>
Case make_case(const char* type, const dds::Topic<T, P>& topic, T (*make)()) {
  return {type, [&topic, make] { round_trip(topic, make()); }};
}

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      make_case("RobotObservationBatch", dds::kRobotObservations, &sample_robot_observations),
      make_case("RobotState", dds::kRobotState, &sample_robot_state),
      make_case("RobotOdometry", dds::kRobotOdometry, &sample_robot_odometry),
      make_case("PoseCorrection", dds::kPoseCorrection, &sample_pose_correction),
      make_case("InitialPose", dds::kInitialPose, &sample_initial_pose),
      make_case("PlacementAnswer", dds::kPlacementAnswer, &sample_placement_answer),
      make_case("GridSnapshot", dds::kGridSnapshot, &sample_grid_snapshot),
      make_case("GridTiles", dds::kGridTiles, &sample_grid_tiles),
      make_case("GridConfig", dds::kGridConfig, &sample_grid_config),
      make_case("MapEdit", dds::kMapEdit, &sample_map_edit),
      make_case("MapFileRequest", dds::kMapFileRequest, &sample_map_file_request),
      make_case("MapReply", dds::kMapReply, &sample_map_reply),
      make_case("NavGoal", dds::kNavGoal, &sample_nav_goal),
      make_case("RobotPath", dds::kRobotPath, &sample_robot_path),
      make_case("WaypointCommand", dds::kWaypointCommand, &sample_waypoint_command),
      make_case("PathRequest", dds::kPathRequest, &sample_path_request),
      make_case("PathReply", dds::kPathReply, &sample_path_reply),
      make_case("MqttTraffic", dds::kMqttTraffic, &sample_mqtt_traffic),
      make_case("MqttRequest", dds::kMqttRequest, &sample_mqtt_request),
      make_case("MqttReply", dds::kMqttReply, &sample_mqtt_reply),
      make_case("MqttSubscriptions", dds::kMqttSubscriptions, &sample_mqtt_subscriptions),
      make_case("SimControl", dds::kSimControl, &sample_sim_control),
      make_case("SimReply", dds::kSimReply, &sample_sim_reply),
      make_case("SimWorld", dds::kSimWorld, &sample_sim_world),
      make_case("SimGroundTruth", dds::kSimGroundTruth, &sample_sim_ground_truth),
      make_case("Heartbeat", dds::kHeartbeat, &sample_heartbeat),
      make_case("Alert", dds::kAlert, &sample_alert),
      make_case("ForgetRobot", dds::kForgetRobot, &sample_forget_robot),
      make_case("FleetDigest", dds::kFleetDigest, &sample_fleet_digest),
      make_case("FleetPoints", dds::kFleetPoints, &sample_fleet_points),
      make_case("RosOccupancyGrid", dds::kRosMap, &sample_ros_occupancy_grid),
      make_case("RosTFMessage", dds::kRosTf, &sample_ros_tf_message),
      make_case("RosPoseStamped", dds::kRosGoalPose, &sample_ros_pose_stamped),
      make_case("RosPoseWithCovarianceStamped", dds::kRosInitialPose,
                &sample_ros_pose_with_covariance_stamped),
  };
  return all;
}

// Topic types in topics.hpp: a new type there must get a case (and a line in cyclone_echo.cpp).
constexpr size_t kTopicTypes = 34;

class InteropTest : public ::testing::TestWithParam<size_t> {};

TEST_P(InteropTest, CrossesFastDdsToCycloneAndBack) {
  cases()[GetParam()].run();
}

INSTANTIATE_TEST_SUITE_P(AllTypes, InteropTest, ::testing::Range<size_t>(0, kTopicTypes),
                         [](const ::testing::TestParamInfo<size_t>& param) {
                           return cases()[param.param].type;
                         });

TEST(InteropCoverageTest, EveryTopicTypeHasACase) {
  EXPECT_EQ(cases().size(), kTopicTypes);
}

}  // namespace
}  // namespace slam::interop

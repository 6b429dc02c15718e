// Cyclone DDS side of the vendor interop test: for every IDL topic type, a Cyclone reader takes
// each sample (decoding it into the idlc-generated C struct) and a Cyclone writer sends that struct
// back on "<topic>/echo". The Fast DDS test compares the echo with what it sent, field by field.
#include <slam/cyclone/correction.h>
#include <slam/cyclone/map.h>
#include <slam/cyclone/mqtt.h>
#include <slam/cyclone/nav.h>
#include <slam/cyclone/robot.h>
#include <slam/cyclone/ros2.h>
#include <slam/cyclone/sim.h>
#include <slam/cyclone/system.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/cyclone/dds.hpp"
#include "interop_topics.hpp"

namespace {

struct EchoTopic {
  const dds_topic_descriptor_t* descriptor;
  slam::topics::TopicInfo info;
};

const EchoTopic kTopics[] = {
    {&slam_RobotObservationBatch_desc, slam::topics::kRobotObservations},
    {&slam_RobotState_desc, slam::topics::kRobotState},
    {&slam_RobotOdometry_desc, slam::topics::kRobotOdometry},
    {&slam_PoseCorrection_desc, slam::topics::kPoseCorrection},
    {&slam_InitialPose_desc, slam::topics::kInitialPose},
    {&slam_PlacementAnswer_desc, slam::topics::kPlacementAnswer},
    {&slam_GridSnapshot_desc, slam::topics::kGridSnapshot},
    {&slam_GridTiles_desc, slam::topics::kGridTiles},
    {&slam_GridConfig_desc, slam::topics::kGridConfig},
    {&slam_MapEdit_desc, slam::topics::kMapEdit},
    {&slam_MapFileRequest_desc, slam::topics::kMapFileRequest},
    {&slam_MapReply_desc, slam::topics::kMapReply},
    {&slam_NavGoal_desc, slam::topics::kNavGoal},
    {&slam_RobotPath_desc, slam::topics::kRobotPath},
    {&slam_WaypointCommand_desc, slam::topics::kWaypointCommand},
    {&slam_PathRequest_desc, slam::topics::kPathRequest},
    {&slam_PathReply_desc, slam::topics::kPathReply},
    {&slam_MqttTraffic_desc, slam::topics::kMqttTraffic},
    {&slam_MqttRequest_desc, slam::topics::kMqttRequest},
    {&slam_MqttReply_desc, slam::topics::kMqttReply},
    {&slam_MqttSubscriptions_desc, slam::topics::kMqttSubscriptions},
    {&slam_SimControl_desc, slam::topics::kSimControl},
    {&slam_SimReply_desc, slam::topics::kSimReply},
    {&slam_SimWorld_desc, slam::topics::kSimWorld},
    {&slam_SimGroundTruth_desc, slam::topics::kSimGroundTruth},
    {&slam_Heartbeat_desc, slam::topics::kHeartbeat},
    {&slam_Alert_desc, slam::topics::kAlert},
    {&slam_ForgetRobot_desc, slam::topics::kForgetRobot},
    {&slam_FleetDigest_desc, slam::topics::kFleetDigest},
    {&slam_FleetPoints_desc, slam::topics::kFleetPoints},
    {&nav_msgs_msg_dds__OccupancyGrid__desc, slam::topics::kRosMap},
    {&tf2_msgs_msg_dds__TFMessage__desc, slam::topics::kRosTf},
    {&geometry_msgs_msg_dds__PoseStamped__desc, slam::topics::kRosGoalPose},
    {&geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc, slam::topics::kRosInitialPose},
};

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) {
  g_stop = 1;
}

struct Pipe {
  slam::cyclone::Entity reader;
  slam::cyclone::Entity writer;
  const char* name;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: interop_cyclone_echo DOMAIN_ID\n");
    return 2;
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  const auto domain = static_cast<dds_domainid_t>(std::atoi(argv[1]));
  slam::cyclone::Entity participant(dds_create_participant(domain, nullptr, nullptr));
  if (!participant.ok()) {
    std::fprintf(stderr, "dds_create_participant: %s\n", dds_strretcode(participant.get()));
    return 1;
  }
  std::vector<Pipe> pipes;
  for (const auto& t : kTopics) {
    auto qos = slam::cyclone::make_qos(t.info.qos);
    const dds_entity_t in =
        dds_create_topic(participant.get(), t.descriptor, t.info.name, qos.get(), nullptr);
    const std::string echo = slam::interop::echo_name(t.info.name);
    const dds_entity_t out =
        dds_create_topic(participant.get(), t.descriptor, echo.c_str(), qos.get(), nullptr);
    if (in < 0 || out < 0) {
      std::fprintf(stderr, "dds_create_topic %s: %s\n", t.info.name, dds_strretcode(in < 0 ? in : out));
      return 1;
    }
    Pipe p{slam::cyclone::Entity(dds_create_reader(participant.get(), in, qos.get(), nullptr)),
           slam::cyclone::Entity(dds_create_writer(participant.get(), out, qos.get(), nullptr)), t.info.name};
    if (!p.reader.ok() || !p.writer.ok()) {
      std::fprintf(stderr, "reader/writer for %s failed\n", t.info.name);
      return 1;
    }
    pipes.push_back(std::move(p));
  }
  std::printf("ready: echoing %zu topics on domain %u\n", pipes.size(), static_cast<unsigned>(domain));
  std::fflush(stdout);

  constexpr int kMax = 16;
  while (!g_stop) {
    bool any = false;
    for (auto& p : pipes) {
      void* samples[kMax] = {};
      dds_sample_info_t infos[kMax];
      const dds_return_t n = dds_take(p.reader.get(), samples, infos, kMax, kMax);
      if (n < 0) {
        std::fprintf(stderr, "dds_take %s: %s\n", p.name, dds_strretcode(n));
        return 1;
      }
      for (int i = 0; i < n; ++i) {
        if (!infos[i].valid_data) continue;
        const dds_return_t rc = dds_write(p.writer.get(), samples[i]);
        if (rc != DDS_RETCODE_OK) std::fprintf(stderr, "dds_write %s: %s\n", p.name, dds_strretcode(rc));
        std::printf("echoed %s\n", p.name);
        any = true;
      }
      if (n > 0) dds_return_loan(p.reader.get(), samples, n);
    }
    std::fflush(stdout);
    if (!any) dds_sleepfor(DDS_MSECS(2));
  }
  return 0;
}

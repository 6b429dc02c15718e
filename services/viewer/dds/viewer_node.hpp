#pragma once
// The viewer's DDS edge: one reader per topic it shows (each converts the sample and pushes it
// into the Intake on the listener thread; nothing else), one writer per command it sends, a
// Requester per reply topic (requests are resent under their id until answered; every reply also
// goes into the Intake), and its heartbeat. configure() undoes itself on failure by returning nothing
// half-built.
#include <atomic>
#include <memory>

#include "common/core/counters.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/heartbeat.hpp"
#include "common/fastdds/requester.hpp"
#include "viewer/core/commands.hpp"
#include "viewer/core/intake.hpp"

namespace slam::viewer {

class ViewerNode final : public CommandSink {
 public:
  static Result<std::unique_ptr<ViewerNode>> configure(int domain, Intake& intake, Counters& counters);
  ~ViewerNode() override;

  void set_running() { heartbeat_->set_state(SERVICE_RUNNING); }
  void set_stopping() { heartbeat_->set_state(SERVICE_STOPPING); }

  uint64_t send(const GoalCommand& c) override;
  uint64_t send(const MapEditCommand& c) override;
  uint64_t send(const GridConfigCommand& c) override;
  uint64_t send(const MqttRequestCommand& c) override;
  uint64_t send(const SimCommand& c) override;
  uint64_t send(const MapFileCommand& c) override;
  uint64_t send(const InitialPoseCommand& c) override;
  uint64_t send(const PlacementAnswerCommand& c) override;
  uint64_t send(const ForgetCommand& c) override;
  uint64_t send(const PathPreviewCommand& c) override;
  uint64_t send(const MissionCommand& c) override;

 private:
  ViewerNode(Intake& intake, Counters& counters);
  Status create_readers();
  Status create_writers();
  // Sends `sample` under a fresh id through `requester` (retried until answered); returns the id.
  template <class Rep, class Req>
  uint64_t request(dds::Requester<Rep>& requester, dds::Writer<Req>& writer, const Req& sample);

  Intake& intake_;
  std::atomic<int64_t>& received_;
  std::atomic<int64_t>& sent_;
  std::atomic<int64_t>& send_failed_;
  RequestIdSource goal_ids_;

  // Declaration order = construction order; members are destroyed in reverse (readers first).
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<HeartbeatPublisher> heartbeat_;
  std::unique_ptr<dds::Writer<NavGoal>> goal_writer_;
  std::unique_ptr<dds::Writer<MapEdit>> edit_writer_;
  std::unique_ptr<dds::Writer<GridConfig>> config_writer_;
  std::unique_ptr<dds::Writer<MqttRequest>> mqtt_writer_;
  std::unique_ptr<dds::Writer<SimControl>> sim_writer_;
  std::unique_ptr<dds::Writer<MapFileRequest>> file_writer_;
  std::unique_ptr<dds::Writer<InitialPose>> initial_pose_writer_;
  std::unique_ptr<dds::Writer<PlacementAnswer>> placement_answer_writer_;
  std::unique_ptr<dds::Writer<ForgetRobot>> forget_writer_;
  std::unique_ptr<dds::Writer<PathRequest>> path_request_writer_;
  std::unique_ptr<dds::Writer<NavMission>> mission_writer_;
  // After the writers they resend through, so they stop first.
  std::unique_ptr<dds::Requester<MapReply>> map_requester_;
  std::unique_ptr<dds::Requester<MqttReply>> mqtt_requester_;
  std::unique_ptr<dds::Requester<SimReply>> sim_requester_;
  std::unique_ptr<dds::Requester<PathReply>> path_requester_;
  std::unique_ptr<dds::Reader<GridSnapshot>> snapshot_reader_;
  std::unique_ptr<dds::Reader<GridTiles>> patch_reader_;
  std::unique_ptr<dds::Reader<RobotObservationBatch>> observation_reader_;
  std::unique_ptr<dds::Reader<RobotState>> state_reader_;
  std::unique_ptr<dds::Reader<RobotPath>> path_reader_;
  std::unique_ptr<dds::Reader<NavMission>> mission_reader_;
  std::unique_ptr<dds::Reader<PoseCorrection>> correction_reader_;
  std::unique_ptr<dds::Reader<FleetDigest>> digest_reader_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader_;
  std::unique_ptr<dds::Reader<MqttTraffic>> traffic_reader_;
  std::unique_ptr<dds::Reader<MqttSubscriptions>> subscriptions_reader_;
  std::unique_ptr<dds::Reader<SimWorld>> world_reader_;
  std::unique_ptr<dds::Reader<SimGroundTruth>> truth_reader_;
  std::unique_ptr<dds::Reader<Alert>> alert_reader_;
  std::unique_ptr<dds::Reader<ForgetRobot>> forget_reader_;
};

}  // namespace slam::viewer

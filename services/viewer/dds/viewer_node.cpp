// The viewer's readers, writers and heartbeat (see viewer_node.hpp).
#include "viewer/dds/viewer_node.hpp"

#include <type_traits>

#include "viewer/core/request_tracker.hpp"
#include "viewer/dds/node_convert.hpp"

namespace slam::viewer {
namespace {

// A reader whose callback converts each sample (each observation of a batch) and pushes it into the
// intake.
template <class T, class PubSubT>
Status make_intake_reader(dds::Participant& p, const dds::Topic<T, PubSubT>& topic, Intake& intake,
                          std::atomic<int64_t>& received, std::unique_ptr<dds::Reader<T>>& out) {
  auto r = dds::make_reader(p, topic, [&intake, &received](const T& sample, const dds::fdds::SampleInfo&) {
    if constexpr (std::is_same_v<T, RobotObservationBatch>) {
      for (const RobotObservation& o : sample.observations()) intake.push(from_idl(o));
    } else if constexpr (std::is_same_v<T, FleetDigest>) {
      for (const DigestRobot& robot : sample.robots()) intake.push(from_idl(robot));
    } else {
      intake.push(from_idl(sample));
    }
    bump(received);
  });
  if (!r) return Error{std::string("reader for ") + topic.info.name + ": " + r.message()};
  out = std::move(*r);
  return {};
}

// A requester on `topic` whose every reply (also to other viewers' requests) goes into the intake.
template <class T, class PubSubT>
Status make_intake_requester(dds::Participant& p, const dds::Topic<T, PubSubT>& topic, Intake& intake,
                             std::atomic<int64_t>& received, std::unique_ptr<dds::Requester<T>>& out) {
  // Retried until the request trackers would call it unanswered.
  RetryPolicy policy;
  policy.timeout =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::nanoseconds(kReplyTimeoutNs));
  auto r = dds::Requester<T>::create(p, topic, policy, [&intake, &received](const T& reply) {
    intake.push(from_idl(reply));
    bump(received);
  });
  if (!r) return Error{std::string("requester on ") + topic.info.name + ": " + r.message()};
  out = std::move(*r);
  return {};
}

template <class T, class PubSubT>
Status make_writer_into(dds::Participant& p, const dds::Topic<T, PubSubT>& topic,
                        std::unique_ptr<dds::Writer<T>>& out) {
  auto w = dds::make_writer(p, topic);
  if (!w) return Error{std::string("writer for ") + topic.info.name + ": " + w.message()};
  out = std::move(*w);
  return {};
}

}  // namespace

ViewerNode::ViewerNode(Intake& intake, Counters& counters)
    : intake_(intake),
      received_(counters.get("samples_received")),
      sent_(counters.get("commands_sent")),
      send_failed_(counters.get("commands_failed")) {}

ViewerNode::~ViewerNode() = default;

Result<std::unique_ptr<ViewerNode>> ViewerNode::configure(int domain, Intake& intake, Counters& counters) {
  std::unique_ptr<ViewerNode> node(new ViewerNode(intake, counters));
  auto participant = dds::Participant::create(domain, "slam-viewer");
  if (!participant) return participant.error();
  node->participant_ = std::move(*participant);
  auto heartbeat = HeartbeatPublisher::start(*node->participant_, "viewer", counters);
  if (!heartbeat) return heartbeat.error();
  node->heartbeat_ = std::move(*heartbeat);
  if (Status s = node->create_writers(); !s) return s.error();
  if (Status s = node->create_readers(); !s) return s.error();
  return node;  // on any error above, `node` is destroyed here with what it had built
}

Status ViewerNode::create_writers() {
  auto& p = *participant_;
  for (Status s :
       {make_writer_into(p, dds::kNavGoal, goal_writer_), make_writer_into(p, dds::kMapEdit, edit_writer_),
        make_writer_into(p, dds::kGridConfig, config_writer_),
        make_writer_into(p, dds::kMqttRequest, mqtt_writer_),
        make_writer_into(p, dds::kSimControl, sim_writer_),
        make_writer_into(p, dds::kMapFileRequest, file_writer_),
        make_writer_into(p, dds::kInitialPose, initial_pose_writer_),
        make_writer_into(p, dds::kPlacementAnswer, placement_answer_writer_),
        make_writer_into(p, dds::kForgetRobot, forget_writer_),
        make_writer_into(p, dds::kPathRequest, path_request_writer_),
        make_writer_into(p, dds::kNavMission, mission_writer_),
        make_intake_requester(p, dds::kMapReply, intake_, received_, map_requester_),
        make_intake_requester(p, dds::kMqttReply, intake_, received_, mqtt_requester_),
        make_intake_requester(p, dds::kSimReply, intake_, received_, sim_requester_),
        make_intake_requester(p, dds::kPathReply, intake_, received_, path_requester_)})
    if (!s) return s;
  return {};
}

Status ViewerNode::create_readers() {
  auto& p = *participant_;
  auto& in = intake_;
  auto& rx = received_;
  for (Status s : {make_intake_reader(p, dds::kGridSnapshot, in, rx, snapshot_reader_),
                   make_intake_reader(p, dds::kGridTiles, in, rx, patch_reader_),
                   make_intake_reader(p, dds::kRobotObservations, in, rx, observation_reader_),
                   make_intake_reader(p, dds::kRobotState, in, rx, state_reader_),
                   make_intake_reader(p, dds::kFleetDigest, in, rx, digest_reader_),
                   make_intake_reader(p, dds::kRobotPath, in, rx, path_reader_),
                   make_intake_reader(p, dds::kNavMission, in, rx, mission_reader_),
                   make_intake_reader(p, dds::kPoseCorrection, in, rx, correction_reader_),
                   make_intake_reader(p, dds::kHeartbeat, in, rx, heartbeat_reader_),
                   make_intake_reader(p, dds::kMqttTraffic, in, rx, traffic_reader_),
                   make_intake_reader(p, dds::kMqttSubscriptions, in, rx, subscriptions_reader_),
                   make_intake_reader(p, dds::kSimWorld, in, rx, world_reader_),
                   make_intake_reader(p, dds::kSimGroundTruth, in, rx, truth_reader_),
                   make_intake_reader(p, dds::kAlert, in, rx, alert_reader_),
                   make_intake_reader(p, dds::kForgetRobot, in, rx, forget_reader_)})
    if (!s) return s;
  return {};
}

uint64_t ViewerNode::send(const GoalCommand& c) {
  // A goal is state (kept for late joiners while this viewer runs), not a request: written once.
  const uint64_t id = goal_ids_.next();
  if (!goal_writer_->write(to_idl(c, id))) {
    bump(send_failed_);
    return 0;
  }
  bump(sent_);
  return id;
}

uint64_t ViewerNode::send(const MissionCommand& c) {
  // Like a goal: state, written once; its id comes from the same source (goals and missions
  // replace each other).
  const uint64_t id = goal_ids_.next();
  if (!mission_writer_->write(to_idl(c, id))) {
    bump(send_failed_);
    return 0;
  }
  bump(sent_);
  return id;
}

template <class Rep, class Req>
uint64_t ViewerNode::request(dds::Requester<Rep>& requester, dds::Writer<Req>& writer, const Req& sample) {
  bump(sent_);
  return requester.send(writer, sample);
}

uint64_t ViewerNode::send(const MapEditCommand& c) {
  return request(*map_requester_, *edit_writer_, to_idl(c, 0));
}
uint64_t ViewerNode::send(const GridConfigCommand& c) {
  return request(*map_requester_, *config_writer_, to_idl(c, 0));
}
uint64_t ViewerNode::send(const MqttRequestCommand& c) {
  return request(*mqtt_requester_, *mqtt_writer_, to_idl(c, 0));
}
uint64_t ViewerNode::send(const SimCommand& c) {
  return request(*sim_requester_, *sim_writer_, to_idl(c, 0));
}
uint64_t ViewerNode::send(const MapFileCommand& c) {
  return request(*map_requester_, *file_writer_, to_idl(c, 0));
}
uint64_t ViewerNode::send(const InitialPoseCommand& c) {
  return request(*map_requester_, *initial_pose_writer_, to_idl(c, 0));
}

uint64_t ViewerNode::send(const PlacementAnswerCommand& c) {
  return request(*map_requester_, *placement_answer_writer_, to_idl(c, 0));
}

uint64_t ViewerNode::send(const ForgetCommand& c) {
  // A command every gateway, planner and viewer acts on; nobody replies (slamctl forget likewise).
  const uint64_t id = goal_ids_.next();
  if (!forget_writer_->write(to_idl(c, id))) {
    bump(send_failed_);
    return 0;
  }
  bump(sent_);
  return id;
}
uint64_t ViewerNode::send(const PathPreviewCommand& c) {
  return request(*path_requester_, *path_request_writer_, to_idl(c, 0));
}

}  // namespace slam::viewer

// The viewer's readers, writers and heartbeat (see viewer_node.hpp).
#include "viewer/dds/viewer_node.hpp"

#include "common/core/clock.hpp"
#include "viewer/dds/node_convert.hpp"

namespace slam::viewer {
namespace {

// A reader whose callback converts each sample and pushes it into the intake.
template <class T, class PubSubT>
Status make_intake_reader(dds::Participant& p, const dds::Topic<T, PubSubT>& topic, Intake& intake,
                          std::atomic<int64_t>& received, std::unique_ptr<dds::Reader<T>>& out) {
  auto r = dds::make_reader(p, topic, [&intake, &received](const T& sample, const dds::fdds::SampleInfo&) {
    intake.push(from_idl(sample));
    bump(received);
  });
  if (!r) return Error{std::string("reader for ") + topic.info.name + ": " + r.message()};
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
      send_failed_(counters.get("commands_failed")),
      next_id_(static_cast<uint64_t>(now_ns())) {}

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
        make_writer_into(p, dds::kInitialPose, initial_pose_writer_)})
    if (!s) return s;
  return {};
}

Status ViewerNode::create_readers() {
  auto& p = *participant_;
  auto& in = intake_;
  auto& rx = received_;
  for (Status s : {make_intake_reader(p, dds::kGridSnapshot, in, rx, snapshot_reader_),
                   make_intake_reader(p, dds::kGridTiles, in, rx, patch_reader_),
                   make_intake_reader(p, dds::kRobotObservation, in, rx, observation_reader_),
                   make_intake_reader(p, dds::kRobotState, in, rx, state_reader_),
                   make_intake_reader(p, dds::kRobotPath, in, rx, path_reader_),
                   make_intake_reader(p, dds::kPoseCorrection, in, rx, correction_reader_),
                   make_intake_reader(p, dds::kHeartbeat, in, rx, heartbeat_reader_),
                   make_intake_reader(p, dds::kMqttTraffic, in, rx, traffic_reader_),
                   make_intake_reader(p, dds::kMqttSubscriptions, in, rx, subscriptions_reader_),
                   make_intake_reader(p, dds::kSimWorld, in, rx, world_reader_),
                   make_intake_reader(p, dds::kSimGroundTruth, in, rx, truth_reader_),
                   make_intake_reader(p, dds::kMapReply, in, rx, reply_reader_),
                   make_intake_reader(p, dds::kMqttReply, in, rx, mqtt_reply_reader_),
                   make_intake_reader(p, dds::kSimReply, in, rx, sim_reply_reader_)})
    if (!s) return s;
  return {};
}

template <class W, class S>
uint64_t ViewerNode::write(W& writer, const S& sample, uint64_t id) {
  if (!writer.write(sample)) {
    bump(send_failed_);
    return 0;
  }
  bump(sent_);
  return id;
}

uint64_t ViewerNode::send(const GoalCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*goal_writer_, to_idl(c, id), id);
}
uint64_t ViewerNode::send(const MapEditCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*edit_writer_, to_idl(c, id), id);
}
uint64_t ViewerNode::send(const GridConfigCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*config_writer_, to_idl(c, id), id);
}
uint64_t ViewerNode::send(const MqttRequestCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*mqtt_writer_, to_idl(c, id), id);
}
uint64_t ViewerNode::send(const SimCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*sim_writer_, to_idl(c, id), id);
}
uint64_t ViewerNode::send(const MapFileCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*file_writer_, to_idl(c, id), id);
}

uint64_t ViewerNode::send(const InitialPoseCommand& c) {
  const uint64_t id = ++next_id_;
  return write(*initial_pose_writer_, to_idl(c, id), id);
}

}  // namespace slam::viewer

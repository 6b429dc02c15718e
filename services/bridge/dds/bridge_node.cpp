// slam-bridge's DDS edge and loop (see bridge_node.hpp).
#include "bridge/dds/bridge_node.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <iterator>

#include "common/core/clock.hpp"
#include "common/core/shutdown.hpp"
#include "common/fastdds/fleet_messages.hpp"

namespace slam::bridge {
namespace {

// Pushes `value` into `queue` under the intake's lock.
template <class Queue, class Value>
void queue(BridgeIntake& intake, Queue& q, Value&& value) {
  std::lock_guard lock(intake.mutex);
  q.push_back(std::forward<Value>(value));
}

}  // namespace

BridgeNode::BridgeNode(const BridgeOptions& options, Counters& counters)
    : received_(counters.get("samples_received")),
      map_skipped_(counters.get("map_patches_skipped")),
      fleet_(options.points_per_robot) {}

BridgeNode::~BridgeNode() = default;

Result<std::unique_ptr<BridgeNode>> BridgeNode::create(const BridgeOptions& options, Counters& counters) {
  std::unique_ptr<BridgeNode> node(new BridgeNode(options, counters));
  auto participant = dds::Participant::create(options.service.domain, "slam-bridge");
  if (!participant) return participant.error();
  node->participant_ = std::move(*participant);
  auto& p = *node->participant_;

  auto goals = dds::make_writer(p, dds::kNavGoal);
  if (!goals) return Error{"writer for NavGoal: " + goals.message()};
  node->goal_writer_ = std::move(*goals);
  auto paths = dds::make_writer(p, dds::kPathRequest);
  if (!paths) return Error{"writer for PathRequest: " + paths.message()};
  node->path_writer_ = std::move(*paths);
  RetryPolicy policy;
  policy.timeout = std::chrono::milliseconds(static_cast<int64_t>(options.path_timeout_s * 1000.0));
  auto requester = dds::Requester<PathReply>::create(p, dds::kPathReply, policy);
  if (!requester) return Error{"requester on PathReply: " + requester.message()};
  node->path_requester_ = std::move(*requester);
  SLAM_TRY(node->create_readers());
  if (options.ros) {
    auto ros = RosEdge::create(p, options, *node, counters);
    if (!ros) return ros.error();
    node->ros_ = std::move(*ros);
  }

  auto bind = parse_bind(options.bind);
  if (!bind) return bind.error();
  auto ws = WsServer::start(bind->host, bind->port, foxglove::kSubprotocol, options.client_backlog_bytes,
                            counters.get("messages_dropped"));
  if (!ws) return ws.error();
  node->ws_ = std::move(*ws);
  const std::string session = std::to_string(::getpid()) + "-" + std::to_string(now_ns());
  node->face_ = std::make_unique<FoxgloveFace>(options.periods, session, *node, *node, counters);
  spdlog::info("bridge: Foxglove WebSocket server on ws://{}:{}", bind->host, node->ws_->port());
  return node;  // on any error above, `node` is destroyed here with what it had built
}

Status BridgeNode::create_readers() {
  auto& p = *participant_;
  auto& in = intake_;
  auto& rx = received_;
  // A reader whose callback converts the sample into the intake; nothing else on that thread.
  auto make = [&](const auto& topic, auto& out, auto convert) -> Status {
    auto r = dds::make_reader(p, topic, [convert, &rx](const auto& sample, const dds::fdds::SampleInfo&) {
      convert(sample);
      bump(rx);
    });
    if (!r) return Error{std::string("reader for ") + topic.info.name + ": " + r.message()};
    out = std::move(*r);
    return {};
  };
  SLAM_TRY(make(dds::kFleetDigest, digest_reader_, [&in](const FleetDigest& d) {
    std::vector<msg::RobotPose> states;
    states.reserve(d.robots().size());
    for (const DigestRobot& r : d.robots()) states.push_back(msg::from_idl(r));
    std::lock_guard lock(in.mutex);
    in.states.insert(in.states.end(), std::make_move_iterator(states.begin()),
                     std::make_move_iterator(states.end()));
  }));
  SLAM_TRY(make(dds::kFleetPoints, points_reader_, [&in](const FleetPoints& f) {
    std::vector<ObservationInput> robots;
    robots.reserve(f.robots().size());
    for (const DigestRobotPoints& r : f.robots()) {
      ObservationInput points{r.robot_id().to_string(), {}};
      points.hits.reserve(r.points().size());
      for (const DigestPoint& d : r.points()) points.hits.push_back({d.x(), d.y()});
      robots.push_back(std::move(points));
    }
    std::lock_guard lock(in.mutex);
    in.observations.insert(in.observations.end(), std::make_move_iterator(robots.begin()),
                           std::make_move_iterator(robots.end()));
  }));
  SLAM_TRY(make(dds::kRobotPath, path_reader_,
                [&in](const RobotPath& s) { queue(in, in.paths, msg::from_idl(s)); }));
  SLAM_TRY(make(dds::kHeartbeat, heartbeat_reader_,
                [&in](const Heartbeat& h) { queue(in, in.heartbeats, msg::from_idl(h)); }));
  SLAM_TRY(
      make(dds::kAlert, alert_reader_, [&in](const Alert& a) { queue(in, in.alerts, msg::from_idl(a)); }));
  SLAM_TRY(make(dds::kForgetRobot, forget_reader_,
                [&in](const ForgetRobot& f) { queue(in, in.forgets, f.robot_id().to_string()); }));
  SLAM_TRY(make(dds::kGridSnapshot, snapshot_reader_,
                [&in](const GridSnapshot& s) { queue(in, in.map, msg::from_idl(s)); }));
  SLAM_TRY(make(dds::kGridTiles, tiles_reader_,
                [&in](const GridTiles& t) { queue(in, in.map, msg::from_idl(t)); }));
  return {};
}

void BridgeNode::drain_intake() {
  BridgeIntake batch;
  {
    std::lock_guard lock(intake_.mutex);
    std::swap(batch.states, intake_.states);
    std::swap(batch.paths, intake_.paths);
    std::swap(batch.observations, intake_.observations);
    std::swap(batch.heartbeats, intake_.heartbeats);
    std::swap(batch.alerts, intake_.alerts);
    std::swap(batch.forgets, intake_.forgets);
    std::swap(batch.map, intake_.map);
    std::swap(batch.answers, intake_.answers);
  }
  const int64_t now = monotonic_ns();
  for (const auto& s : batch.states) fleet_.ingest(s);
  for (auto& p : batch.paths) fleet_.ingest(std::move(p));
  for (const auto& o : batch.observations) fleet_.ingest(o);
  for (auto& h : batch.heartbeats) fleet_.ingest(std::move(h), now);
  for (auto& a : batch.alerts) fleet_.ingest(std::move(a));
  for (const std::string& id : batch.forgets) fleet_.forget(id);
  for (auto& m : batch.map) {
    const Status s = std::visit([this](auto& input) { return map_.ingest(std::move(input)); }, m);
    if (!s) {
      bump(map_skipped_);
      log_.warn("map", "bridge: {}", s.message());
    }
  }
  for (const auto& [call, answer] : batch.answers) face_->answer(call, answer);
}

void BridgeNode::run_once() {
  wait_for_shutdown(kLoopPeriod);
  for (const ClientEvent& e : ws_->take_events()) {
    switch (e.kind) {
      case ClientEvent::Kind::Connected:
        face_->connect(e.client);
        break;
      case ClientEvent::Kind::Disconnected:
        face_->disconnect(e.client);
        break;
      case ClientEvent::Kind::Text:
        face_->receive_text(e.client, e.bytes);
        break;
      case ClientEvent::Kind::Binary:
        face_->receive_binary(e.client, e.bytes);
        break;
    }
  }
  drain_intake();
  const int64_t now_mono = monotonic_ns(), stamp = now_ns();
  face_->publish(fleet_, map_, now_mono, stamp);
  if (ros_) ros_->run_once(fleet_, map_, now_mono, stamp);
}

void BridgeNode::send_goal(const GoalCommand& goal) {
  NavGoal sample;
  sample.robot_id(goal.robot_id);
  sample.goal_id(goal_ids_.next());
  sample.mode(msg::to_idl(goal.mode));
  sample.target(msg::to_idl(goal.target));
  if (!goal_writer_->write(sample)) log_.warn("goal", "bridge: goal for {} not written", goal.robot_id);
  spdlog::info("bridge: goal {} for {} ({}, {})", sample.goal_id(), goal.robot_id, goal.target.x,
               goal.target.y);
}

void BridgeNode::request_path(const PathCall& call) {
  PathRequest request;
  request.client_id("bridge");
  request.start(msg::to_idl(call.query.start));
  request.goal(msg::to_idl(call.query.goal));
  request.algorithm(call.query.algorithm);
  request.time_budget_s(call.query.time_budget_s);
  // The answer comes back on a DDS thread and goes through the intake to the loop.
  path_requester_->send(*path_writer_, request, [this, call](const std::optional<PathReply>& reply) {
    std::optional<msg::PathReply> answer;
    if (reply) answer = msg::from_idl(*reply);
    queue(intake_, intake_.answers, std::make_pair(call, std::move(answer)));
  });
}

}  // namespace slam::bridge

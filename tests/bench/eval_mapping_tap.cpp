// What an eval_mapping run hears on DDS (eval_mapping_tap.hpp).
#include "eval_mapping_tap.hpp"

#include <fmt/format.h>

namespace slam::bench {

namespace {

Pose to_pose(const Pose2& p) {
  return {p.x(), p.y(), p.theta()};
}

template <class T, class P, class F>
Status open(dds::Participant& participant, std::unique_ptr<dds::Reader<T>>& out,
            const dds::Topic<T, P>& topic, F on_sample) {
  auto r = dds::make_reader(participant, topic, [on_sample](const T& s, const auto&) { on_sample(s); });
  if (!r) return Error{fmt::format("{} reader: {}", topic.info.name, r.message())};
  out = std::move(*r);
  return Status::ok();
}

template <class T, class P>
Status open(dds::Participant& participant, std::unique_ptr<dds::Writer<T>>& out,
            const dds::Topic<T, P>& topic) {
  auto w = dds::make_writer(participant, topic);
  if (!w) return Error{fmt::format("{} writer: {}", topic.info.name, w.message())};
  out = std::move(*w);
  return Status::ok();
}

}  // namespace

Result<std::unique_ptr<SystemTap>> SystemTap::create(int domain, RunRecorder& recorder) {
  std::unique_ptr<SystemTap> tap(new SystemTap(recorder));
  SLAM_TRY(tap->connect(domain));
  return tap;
}

int64_t SystemTap::counter(const std::string& service, const std::string& name) const {
  std::lock_guard lock(mutex_);
  const auto s = counters_.find(service);
  if (s == counters_.end()) return -1;
  const auto c = s->second.find(name);
  return c == s->second.end() ? -1 : c->second;
}

std::map<std::string, int64_t> SystemTap::counters(const std::string& service,
                                                   const std::string& prefix) const {
  std::lock_guard lock(mutex_);
  std::map<std::string, int64_t> out;
  const auto s = counters_.find(service);
  if (s == counters_.end()) return out;
  for (const auto& [name, value] : s->second)
    if (name.starts_with(prefix)) out[name] = value;
  return out;
}

std::optional<SimWorld> SystemTap::world() const {
  std::lock_guard lock(mutex_);
  return world_;
}

bool SystemTap::goal_ended(uint64_t goal_id, size_t robots) const {
  std::lock_guard lock(mutex_);
  size_t ended = 0;
  for (const auto& [robot, status] : goal_status_)
    if (status.first == goal_id &&
        (status.second == GOAL_STATUS_REACHED || status.second == GOAL_STATUS_FAILED))
      ++ended;
  return ended >= robots;
}

std::optional<MapReply> SystemTap::reply(uint64_t id) const {
  std::lock_guard lock(mutex_);
  const auto it = replies_.find(id);
  return it == replies_.end() ? std::nullopt : std::optional<MapReply>(it->second);
}

Status SystemTap::connect(int domain) {
  auto participant = dds::Participant::create(domain, "eval-mapping");
  if (!participant) return Error{"DDS participant: " + participant.message()};
  participant_ = std::move(*participant);
  dds::Participant& p = *participant_;
  SLAM_TRY(open(p, truth_, dds::kSimGroundTruth, [this](const SimGroundTruth& t) {
    std::vector<RobotTruth> robots;
    for (const SimRobotTruth& r : t.robots())
      robots.push_back({r.robot_id().to_string(), to_pose(r.true_pose()), to_pose(r.reported_pose())});
    recorder_.on_truth(t.stamp_ns(), robots);
  }));
  SLAM_TRY(open(p, digests_, dds::kFleetDigest, [this](const FleetDigest& d) {
    for (const DigestRobot& r : d.robots())
      recorder_.on_published_pose(r.robot_id().to_string(), {r.pose().x(), r.pose().y()});
  }));
  SLAM_TRY(open(p, corrections_, dds::kPoseCorrection, [this](const PoseCorrection& c) {
    recorder_.on_correction(c.robot_id().to_string(), to_pose(c.map_from_odom()), c.version(),
                            c.source() == CORRECTION_LOOP, c.placement() == PLACEMENT_PLACED);
  }));
  SLAM_TRY(open(p, paths_, dds::kRobotPath, [this](const RobotPath& path) {
    PathView view{path.goal_id(), {}, path.current()};
    for (const Point2& w : path.waypoints()) view.waypoints.push_back({w.x(), w.y()});
    recorder_.on_path(path.robot_id().to_string(), view);
    std::lock_guard lock(mutex_);
    goal_status_[path.robot_id().to_string()] = {path.goal_id(), path.status()};
  }));
  SLAM_TRY(open(p, worlds_, dds::kSimWorld, [this](const SimWorld& w) {
    std::lock_guard lock(mutex_);
    world_ = w;
  }));
  SLAM_TRY(open(p, heartbeats_, dds::kHeartbeat, [this](const Heartbeat& h) {
    std::lock_guard lock(mutex_);
    auto& counters = counters_[h.service().to_string()];
    for (const Counter& c : h.counters()) counters[c.name().to_string()] = c.value();
  }));
  SLAM_TRY(open(p, replies_reader_, dds::kMapReply, [this](const MapReply& r) {
    std::lock_guard lock(mutex_);
    replies_[r.request_id()] = r;
  }));
  SLAM_TRY(open(p, goals_, dds::kNavGoal));
  SLAM_TRY(open(p, files_, dds::kMapFileRequest));
  SLAM_TRY(open(p, missions_, dds::kNavMission));
  return Status::ok();
}

std::vector<sim::Segment> walls_of(const SimWorld& world) {
  std::vector<sim::Segment> out;
  for (const Segment2& w : world.walls()) out.push_back({{w.a().x(), w.a().y()}, {w.b().x(), w.b().y()}});
  return out;
}

}  // namespace slam::bench

#include "slamctl/commands.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include "common/core/clock.hpp"
#include "common/core/shutdown.hpp"
#include "slamctl/format.hpp"

namespace slam::ctl {
namespace {

using namespace std::chrono_literals;

int fail(const std::string& why) {
  std::cerr << "slamctl: " << why << "\n";
  return 1;
}

bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() >= until || shutdown_requested()) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

// Writes one sample to whoever serves `topic` (waits for a reader first, then for its ack).
template <class T, class P>
int send(Session& s, const dds::Topic<T, P>& topic, const T& sample, const char* served_by) {
  auto writer = dds::make_writer(s.participant(), topic);
  if (!writer) return fail(writer.message());
  if (!(*writer)->wait_for_readers(s.timeout()))
    return fail(std::string("no ") + served_by + " on DDS domain " + std::to_string(s.domain()) +
                " (is it running?)");
  if (!(*writer)->write(sample)) return fail(std::string("could not write to ") + topic.info.name);
  if (!(*writer)->wait_for_acknowledgments(s.timeout()))
    return fail(std::string(served_by) + " did not acknowledge the request");
  return 0;
}

// Sends a request and waits for the reply with the same request_id.
template <class Req, class ReqP, class Rep, class RepP>
std::optional<Rep> request(Session& s, const dds::Topic<Req, ReqP>& req_topic, const Req& req,
                           const dds::Topic<Rep, RepP>& rep_topic, const char* served_by) {
  std::mutex mutex;
  std::optional<Rep> reply;
  auto reader = dds::make_reader(s.participant(), rep_topic, [&](const Rep& r, const auto&) {
    if (r.request_id() != req.request_id()) return;
    std::lock_guard lock(mutex);
    reply = r;
  });
  if (!reader) {
    fail(reader.message());
    return std::nullopt;
  }
  // The replier's writer must know this reader before it answers, or the reply goes nowhere.
  if (!(*reader)->wait_for_writers(s.timeout())) {
    fail(std::string("no ") + served_by + " on DDS domain " + std::to_string(s.domain()) +
         " (is it running?)");
    return std::nullopt;
  }
  if (send(s, req_topic, req, served_by) != 0) return std::nullopt;
  if (!wait_until(
          [&] {
            std::lock_guard lock(mutex);
            return reply.has_value();
          },
          s.timeout())) {
    fail(std::string("no reply from ") + served_by + " within " + std::to_string(s.timeout().count()) +
         " ms");
    return std::nullopt;
  }
  std::lock_guard lock(mutex);
  return reply;
}

// The latest sample per key of a state topic, collected on the reader's thread.
template <class T>
class Latest {
 public:
  template <class P, class Key>
  Latest(Session& s, const dds::Topic<T, P>& topic, Key key) {
    auto reader = dds::make_reader(s.participant(), topic, [this, key](const T& sample, const auto&) {
      std::lock_guard lock(mutex_);
      latest_[key(sample)] = sample;
    });
    if (!reader) {
      fail(reader.message());
      return;
    }
    reader_ = std::move(*reader);
  }
  bool ok() const { return reader_ != nullptr; }
  bool matched() const { return reader_ && reader_->matched_writers() > 0; }
  std::map<std::string, T> take() {
    reader_.reset();
    std::lock_guard lock(mutex_);
    return std::move(latest_);
  }

 private:
  std::mutex mutex_;
  std::map<std::string, T> latest_;
  std::unique_ptr<dds::Reader<T>> reader_;
};

// Listens for `listen` once `first` matched a writer (nothing to hear when none did within the
// timeout): discovery alone can take seconds, and the samples kept for late joiners arrive only after it.
template <class T>
void listen_after_match(Session& s, const Latest<T>& first, std::chrono::milliseconds listen) {
  if (wait_until([&] { return first.matched(); }, s.timeout())) wait_for_shutdown(listen);
}

template <class T, class P>
int echo(Session& s, const dds::Topic<T, P>& topic, int count) {
  std::atomic<int> seen{0};
  auto reader = dds::make_reader(s.participant(), topic, [&](const T& sample, const auto&) {
    if (count > 0 && seen >= count) return;
    std::printf("%s\n", describe(sample).c_str());
    std::fflush(stdout);
    ++seen;
  });
  if (!reader) return fail(reader.message());
  while (!shutdown_requested() && (count <= 0 || seen < count)) std::this_thread::sleep_for(20ms);
  return 0;
}

}  // namespace

uint64_t Session::next_request_id() {
  return (static_cast<uint64_t>(getpid()) << 32) ^ (static_cast<uint64_t>(now_ns()) & 0xffff0000ULL) ^
         ++sequence_;
}

int cmd_status(Session& s) {
  Latest<Heartbeat> beats(s, dds::kHeartbeat, [](const Heartbeat& h) {
    return h.service().to_string() + "/" + h.instance_id().to_string();
  });
  if (!beats.ok()) return 1;
  // Heartbeats come once a second: listen a little longer than that.
  listen_after_match(s, beats, std::min<std::chrono::milliseconds>(s.timeout(), 2500ms));
  const auto seen = beats.take();
  if (seen.empty()) return fail("no service seen on DDS domain " + std::to_string(s.domain()));
  const int64_t now = now_ns();
  for (const auto& [key, hb] : seen) std::printf("%s", format_heartbeat(hb, now).c_str());
  return 0;
}

int cmd_robots(Session& s) {
  Latest<RobotPath> paths(s, dds::kRobotPath, [](const RobotPath& p) { return p.robot_id().to_string(); });
  Latest<RobotState> states(s, dds::kRobotState,
                            [](const RobotState& r) { return r.robot_id().to_string(); });
  if (!paths.ok() || !states.ok()) return 1;
  // Paths are optional (no planner, no paths): the window follows the robot states' writer.
  listen_after_match(s, states, std::min<std::chrono::milliseconds>(s.timeout(), 1500ms));
  const auto path_of = paths.take();
  const auto robots = states.take();
  if (robots.empty()) return fail("no robot known on DDS domain " + std::to_string(s.domain()));
  const int64_t now = now_ns();
  for (const auto& [id, st] : robots) {
    auto it = path_of.find(id);
    std::printf("%s", format_robot(st, it == path_of.end() ? nullptr : &it->second, now).c_str());
  }
  return 0;
}

int cmd_goal(Session& s, const std::string& robot, GoalMode mode, const Point2& target, double square_size,
             bool centred) {
  NavGoal goal;
  goal.robot_id(robot == "all" ? "*" : robot);
  goal.goal_id(s.next_request_id());
  goal.mode(mode);
  goal.target(target);
  goal.square_size(square_size);
  goal.square_anchor(centred ? SQUARE_CENTRED : SQUARE_CORNER);
  const int rc = send(s, dds::kNavGoal, goal, "planner");
  if (rc == 0) std::printf("goal %s sent to %s\n", goal_mode_name(mode).c_str(), robot.c_str());
  return rc;
}

int cmd_path(Session& s, const Point2& start, const Point2& goal, const std::string& algorithm,
             double budget_s) {
  PathRequest req;
  req.request_id(s.next_request_id());
  req.client_id("slamctl:" + std::to_string(getpid()));
  req.start(start);
  req.goal(goal);
  req.algorithm(algorithm);
  req.time_budget_s(budget_s);
  const auto reply = request(s, dds::kPathRequest, req, dds::kPathReply, "planner");
  if (!reply) return 1;
  std::printf("%s", format_path_reply(*reply).c_str());
  return reply->status() == PLAN_OK ? 0 : 1;
}

int cmd_map_file(Session& s, MapFileAction action, const std::string& yaml_path) {
  MapFileRequest req;
  req.request_id(s.next_request_id());
  req.action(action);
  req.yaml_path(yaml_path);
  const auto reply = request(s, dds::kMapFileRequest, req, dds::kMapReply, "mapper");
  if (!reply) return 1;
  if (reply->result() != MAP_OK)
    return fail(map_result_name(reply->result()) + ": " + reply->message().to_string());
  std::printf("%s\n", reply->message().c_str());
  return 0;
}

int cmd_grid(Session& s, const GridConfig& config) {
  GridConfig c = config;
  c.request_id(s.next_request_id());
  return send(s, dds::kGridConfig, c, "mapper");
}

int cmd_map_edit(Session& s, MapEditKind kind, const Point2& point, const std::string& robot) {
  MapEdit edit;
  edit.request_id(s.next_request_id());
  edit.kind(kind);
  edit.point(point);
  edit.robot_id(robot);
  return send(s, dds::kMapEdit, edit, "mapper");
}

int cmd_sim(Session& s, SimCommandKind kind, uint32_t count, const std::string& robot) {
  SimControl c;
  c.command_id(s.next_request_id());
  c.kind(kind);
  c.count(count);
  c.robot_id(robot);
  c.speed_factor(1.0);
  return send(s, dds::kSimControl, c, "simulator");
}

int cmd_echo(Session& s, const std::string& topic, int count) {
  if (topic == topics::kRobotObservation.name) return echo(s, dds::kRobotObservation, count);
  if (topic == topics::kRobotState.name) return echo(s, dds::kRobotState, count);
  if (topic == topics::kGridSnapshot.name) return echo(s, dds::kGridSnapshot, count);
  if (topic == topics::kGridPatch.name) return echo(s, dds::kGridPatch, count);
  if (topic == topics::kRobotPath.name) return echo(s, dds::kRobotPath, count);
  if (topic == topics::kWaypointCommand.name) return echo(s, dds::kWaypointCommand, count);
  if (topic == topics::kNavGoal.name) return echo(s, dds::kNavGoal, count);
  if (topic == topics::kMqttTraffic.name) return echo(s, dds::kMqttTraffic, count);
  if (topic == topics::kSimGroundTruth.name) return echo(s, dds::kSimGroundTruth, count);
  if (topic == topics::kHeartbeat.name) return echo(s, dds::kHeartbeat, count);
  if (topic == topics::kMapReply.name) return echo(s, dds::kMapReply, count);
  if (topic == topics::kPathReply.name) return echo(s, dds::kPathReply, count);
  return fail("cannot echo '" + topic + "': see docs/topics.md for topic names");
}

}  // namespace slam::ctl

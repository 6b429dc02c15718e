#pragma once
// slamctl's commands: each one a function that talks DDS through a Session and returns the process
// exit code (0 done, 1 failed or timed out, with a one-line reason on stderr).
#include <chrono>
#include <memory>
#include <string>

#include "common/fastdds/fast_topics.hpp"

namespace slam::ctl {

class Session {
 public:
  Session(std::unique_ptr<dds::Participant> participant, std::chrono::milliseconds timeout)
      : participant_(std::move(participant)), timeout_(timeout) {}
  dds::Participant& participant() { return *participant_; }
  std::chrono::milliseconds timeout() const { return timeout_; }
  int domain() const { return participant_->domain_id(); }
  // A request id unlikely to collide with another client's.
  uint64_t next_request_id();

 private:
  std::unique_ptr<dds::Participant> participant_;
  std::chrono::milliseconds timeout_;
  uint64_t sequence_ = 0;
};

int cmd_status(Session& s);
int cmd_robots(Session& s);
int cmd_goal(Session& s, const std::string& robot, GoalMode mode, const Point2& target, double square_size,
             bool centred);
int cmd_path(Session& s, const Point2& start, const Point2& goal, const std::string& algorithm,
             double budget_s);
int cmd_map_file(Session& s, MapFileAction action, const std::string& yaml_path);
int cmd_grid(Session& s, const GridConfig& config);
int cmd_map_edit(Session& s, MapEditKind kind, const Point2& point, const std::string& robot);
int cmd_sim(Session& s, SimCommandKind kind, uint32_t count, const std::string& robot);
int cmd_echo(Session& s, const std::string& topic, int count);

}  // namespace slam::ctl

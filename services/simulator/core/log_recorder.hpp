#pragma once
// slam-simulator --record-log PREFIX: what each simulated robot senses, kept as a benchmark log
// would be. While the simulation runs, each report's scan is appended to PREFIX-<robot>.clf
// (CARMEN text, carmen_writer.hpp) with the robot's drifting odometry pose; when recording
// finishes, PREFIX-<robot>.relations gets the relations of the robot's true poses at those scans
// (truth_relations.hpp). A pair stands in for a benchmark log: played with --play, scored against
// the relations. Plain C++ on files.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "simulator/core/report.hpp"
#include "simulator/core/truth_relations.hpp"

namespace slam::sim {

class LogRecorder {
 public:
  // An error when PREFIX's directory does not exist or the plan is invalid; a robot's files are
  // created at its first report (a robot spawned later gets its own).
  static Result<LogRecorder> create(std::string prefix, std::string world_name, RelationPlan plan = {});

  // Appends the report's scan to its robot's log; an error when that log cannot be opened or written.
  Status add(const RobotReport& report);
  // Writes every robot's relation file and closes the logs; later reports are refused. The first
  // failure is returned, after every robot has been tried.
  Status finish();

  std::filesystem::path log_path(std::string_view robot_id) const;
  std::filesystem::path relations_path(std::string_view robot_id) const;
  size_t robots() const { return robots_.size(); }
  int64_t scans() const { return scans_; }
  int64_t relations() const { return relations_; }  // written by finish()

 private:
  struct RobotRecord {
    std::ofstream log;
    std::vector<TruthSample> truth;
  };

  LogRecorder(std::string prefix, std::string world_name, RelationPlan plan)
      : prefix_(std::move(prefix)), world_name_(std::move(world_name)), plan_(plan) {}
  Result<RobotRecord*> record_of(const std::string& robot_id);
  Status write_relations(const std::string& robot_id, const RobotRecord& record);

  std::string prefix_;
  std::string world_name_;
  RelationPlan plan_;
  std::map<std::string, RobotRecord> robots_;
  std::string line_;  // reused for every line
  int64_t scans_ = 0;
  int64_t relations_ = 0;
  bool finished_ = false;
};

}  // namespace slam::sim

// Simulated robots' logs and relation files (log_recorder.hpp).
#include "simulator/core/log_recorder.hpp"

#include <fmt/format.h>

#include <system_error>

#include "simulator/core/carmen_writer.hpp"

namespace slam::sim {

Result<LogRecorder> LogRecorder::create(std::string prefix, std::string world_name, RelationPlan plan) {
  if (auto s = plan.validate(); !s) return Error{"relation plan: " + s.message()};
  if (prefix.empty()) return Error{"the log prefix is empty"};
  const std::filesystem::path dir = std::filesystem::path(prefix).parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    return Error{fmt::format("directory {} does not exist", dir.string())};
  return LogRecorder(std::move(prefix), std::move(world_name), plan);
}

std::filesystem::path LogRecorder::log_path(std::string_view robot_id) const {
  return fmt::format("{}-{}.clf", prefix_, robot_id);
}

std::filesystem::path LogRecorder::relations_path(std::string_view robot_id) const {
  return fmt::format("{}-{}.relations", prefix_, robot_id);
}

Result<LogRecorder::RobotRecord*> LogRecorder::record_of(const std::string& robot_id) {
  if (auto it = robots_.find(robot_id); it != robots_.end()) return &it->second;
  const auto path = log_path(robot_id);
  RobotRecord record;
  record.log.open(path, std::ios::binary | std::ios::trunc);
  if (!record.log) return Error{fmt::format("{}: cannot open for writing", path.string())};
  record.log << carmen_header(robot_id, world_name_);
  return &robots_.emplace(robot_id, std::move(record)).first->second;
}

Status LogRecorder::add(const RobotReport& report) {
  if (finished_) return Error{"the recording is finished"};
  auto record = record_of(report.robot_id);
  if (!record) return record.error();
  line_.clear();
  append_robotlaser_line(report, line_);
  (*record)->log.write(line_.data(), static_cast<std::streamsize>(line_.size()));
  if (!(*record)->log) return Error{fmt::format("{}: write error", log_path(report.robot_id).string())};
  (*record)->truth.push_back({report.time_s, report.true_pose});
  ++scans_;
  return Status::ok();
}

Status LogRecorder::write_relations(const std::string& robot_id, const RobotRecord& record) {
  const auto relations = pick_relations(record.truth, plan_);
  // No comment lines: the benchmark's own tools read numbers only.
  std::string text;
  for (const TruthRelation& r : relations) append_relation_line(r, text);
  const auto path = relations_path(robot_id);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) return Error{fmt::format("{}: cannot open for writing", path.string())};
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.flush();
  if (!file) return Error{fmt::format("{}: write error", path.string())};
  relations_ += static_cast<int64_t>(relations.size());
  return Status::ok();
}

Status LogRecorder::finish() {
  if (finished_) return Status::ok();
  finished_ = true;
  Status first;
  for (auto& [id, record] : robots_) {
    record.log.flush();
    if (!record.log && first) first = Error{fmt::format("{}: write error", log_path(id).string())};
    record.log.close();
    if (auto s = write_relations(id, record); !s && first) first = s;
  }
  return first;
}

}  // namespace slam::sim

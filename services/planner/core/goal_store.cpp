// GoalStore: the goal file's format, and keeping it current.
#include "planner/core/goal_store.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "planner/core/fleet.hpp"

namespace slam::planner {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "slam-planner-goals";
constexpr int kVersion = 1;
constexpr size_t kMaxRobotId = 64;  // NavGoal.robot_id is a string<64>

template <size_t N>
Result<size_t> name_index(const json& value, const std::array<const char*, N>& names, const char* what) {
  if (value.is_string()) {
    const auto& text = value.get_ref<const std::string&>();
    for (size_t i = 0; i < N; ++i)
      if (text == names[i]) return i;
  }
  std::string list;
  for (const char* n : names) list += (list.empty() ? "" : ", ") + std::string(n);
  return Error{std::string(what) + " must be one of " + list + ", got " + value.dump()};
}

Result<Vec2> to_point(const json& value, const std::string& what) {
  if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
    return Error{what + " must be [x, y] in metres"};
  const Vec2 p{value[0].get<double>(), value[1].get<double>()};
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return Error{what + " is not finite"};
  return p;
}

Result<std::string> to_robot_id(const json& value, const std::string& what) {
  if (!value.is_string()) return Error{what + " must be a string"};
  const auto& id = value.get_ref<const std::string&>();
  if (id.empty() || id.size() > kMaxRobotId) return Error{what + " must be 1 to 64 characters"};
  return id;
}

Result<StoredGoal> to_stored_goal(const json& item, size_t index) {
  const std::string where = "goals[" + std::to_string(index) + "]";
  if (!item.is_object()) return Error{where + " must be an object"};
  for (const char* key : {"robot_id", "goal_id", "mode", "target", "sent_ns", "finished"}) {
    if (!item.contains(key)) return Error{where + " has no \"" + key + "\""};
  }
  StoredGoal out;
  auto id = to_robot_id(item["robot_id"], where + ".robot_id");
  if (!id) return id.error();
  out.robot_id = *id;
  if (!item["goal_id"].is_number_unsigned()) return Error{where + ".goal_id must be a non-negative integer"};
  out.goal.goal_id = item["goal_id"].get<uint64_t>();
  auto mode = name_index(item["mode"], msg::kGoalModeNames, (where + ".mode").c_str());
  if (!mode) return mode.error();
  out.goal.mode = static_cast<GoalMode>(*mode);
  auto target = to_point(item["target"], where + ".target");
  if (!target) return target.error();
  out.goal.target = *target;
  if (item.contains("square_size")) {
    const json& size = item["square_size"];
    if (!size.is_number() || !std::isfinite(size.get<double>()))
      return Error{where + ".square_size must be a finite number"};
    out.goal.square_size = size.get<double>();
  }
  if (item.contains("square_anchor")) {
    auto anchor =
        name_index(item["square_anchor"], msg::kSquareAnchorNames, (where + ".square_anchor").c_str());
    if (!anchor) return anchor.error();
    out.goal.square_anchor = static_cast<SquareAnchor>(*anchor);
  }
  if (!item["sent_ns"].is_number_integer()) return Error{where + ".sent_ns must be an integer"};
  out.sent_ns = item["sent_ns"].get<int64_t>();
  if (!item["finished"].is_boolean()) return Error{where + ".finished must be true or false"};
  out.finished = item["finished"].get<bool>();
  if (auto s = validate(out.goal); !s) return Error{where + ": " + s.message()};
  return out;
}

Result<StoredMission> to_stored_mission(const json& item, size_t index) {
  const std::string where = "missions[" + std::to_string(index) + "]";
  if (!item.is_object()) return Error{where + " must be an object"};
  for (const char* key :
       {"robot_id", "mission_id", "waypoints", "loop", "current", "laps", "status", "sent_ns"}) {
    if (!item.contains(key)) return Error{where + " has no \"" + key + "\""};
  }
  StoredMission out;
  auto id = to_robot_id(item["robot_id"], where + ".robot_id");
  if (!id) return id.error();
  out.robot_id = *id;
  if (!item["mission_id"].is_number_unsigned())
    return Error{where + ".mission_id must be a non-negative integer"};
  out.mission.mission_id = item["mission_id"].get<uint64_t>();
  const json& waypoints = item["waypoints"];
  if (!waypoints.is_array()) return Error{where + ".waypoints must be an array of [x, y]"};
  for (size_t i = 0; i < waypoints.size(); ++i) {
    auto p = to_point(waypoints[i], where + ".waypoints[" + std::to_string(i) + "]");
    if (!p) return p.error();
    out.mission.waypoints.push_back(*p);
  }
  if (!item["loop"].is_boolean()) return Error{where + ".loop must be true or false"};
  out.mission.loop = item["loop"].get<bool>();
  if (!item["current"].is_number_unsigned()) return Error{where + ".current must be a non-negative integer"};
  out.progress.current = item["current"].get<size_t>();
  if (!item["laps"].is_number_unsigned()) return Error{where + ".laps must be a non-negative integer"};
  out.progress.laps = item["laps"].get<uint32_t>();
  auto status = name_index(item["status"], msg::kMissionStatusNames, (where + ".status").c_str());
  if (!status) return status.error();
  out.progress.status = static_cast<MissionStatus>(*status);
  if (item.contains("reason")) {
    if (!item["reason"].is_string()) return Error{where + ".reason must be a string"};
    out.progress.reason = item["reason"].get<std::string>();
  }
  if (!item["sent_ns"].is_number_integer()) return Error{where + ".sent_ns must be an integer"};
  out.sent_ns = item["sent_ns"].get<int64_t>();
  if (auto s = validate(out.mission, out.progress); !s) return Error{where + ": " + s.message()};
  return out;
}

// Robot ids come off the network: invalid UTF-8 is replaced rather than failing the save.
std::string dump(const nlohmann::ordered_json& value) {
  return value.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace

Result<GoalRecord> parse_goal_record(std::string_view text) {
  const json doc = json::parse(text.begin(), text.end(), nullptr, false);
  if (doc.is_discarded()) return Error{"not valid JSON"};
  if (!doc.is_object()) return Error{"must be a JSON object"};
  if (!doc.contains("format") || doc["format"] != kFormat)
    return Error{std::string("\"format\" must be \"") + kFormat + "\""};
  if (!doc.contains("version") || doc["version"] != kVersion)
    return Error{"\"version\" must be " + std::to_string(kVersion) + " (written by a newer planner?)"};
  GoalRecord record;
  if (doc.contains("goals")) {
    const json& goals = doc["goals"];
    if (!goals.is_array()) return Error{"\"goals\" must be an array"};
    for (size_t i = 0; i < goals.size(); ++i) {
      auto goal = to_stored_goal(goals[i], i);
      if (!goal) return goal.error();
      const std::string id = goal->robot_id;
      if (!record.goals.emplace(id, std::move(*goal)).second)
        return Error{"goals[" + std::to_string(i) + "]: a second goal for robot '" + id + "'"};
    }
  }
  if (doc.contains("missions")) {
    const json& missions = doc["missions"];
    if (!missions.is_array()) return Error{"\"missions\" must be an array"};
    for (size_t i = 0; i < missions.size(); ++i) {
      auto mission = to_stored_mission(missions[i], i);
      if (!mission) return mission.error();
      const std::string id = mission->robot_id;
      if (!record.missions.emplace(id, std::move(*mission)).second)
        return Error{"missions[" + std::to_string(i) + "]: a second mission for robot '" + id + "'"};
    }
  }
  if (doc.contains("homes")) {
    const json& homes = doc["homes"];
    if (!homes.is_object()) return Error{"\"homes\" must be an object of robot_id: [x, y]"};
    for (const auto& [key, value] : homes.items()) {
      auto id = to_robot_id(json(key), "homes key '" + key + "'");
      if (!id) return id.error();
      auto home = to_point(value, "homes." + key);
      if (!home) return home.error();
      record.homes.emplace(*id, *home);
    }
  }
  return record;
}

std::string format_goal_record(const GoalRecord& record) {
  // One goal per line: small enough to read and to diff by hand.
  std::string goals;
  for (const auto& [id, g] : record.goals) {
    const nlohmann::ordered_json goal{{"robot_id", id},
                                      {"goal_id", g.goal.goal_id},
                                      {"mode", msg::goal_mode_name(g.goal.mode)},
                                      {"target", {g.goal.target.x, g.goal.target.y}},
                                      {"square_size", g.goal.square_size},
                                      {"square_anchor", msg::square_anchor_name(g.goal.square_anchor)},
                                      {"sent_ns", g.sent_ns},
                                      {"finished", g.finished}};
    goals += (goals.empty() ? "\n  " : ",\n  ") + dump(goal);
  }
  std::string missions;
  for (const auto& [id, m] : record.missions) {
    nlohmann::ordered_json waypoints = nlohmann::ordered_json::array();
    for (const Vec2& p : m.mission.waypoints) waypoints.push_back({p.x, p.y});
    const nlohmann::ordered_json mission{{"robot_id", id},
                                         {"mission_id", m.mission.mission_id},
                                         {"waypoints", waypoints},
                                         {"loop", m.mission.loop},
                                         {"current", m.progress.current},
                                         {"laps", m.progress.laps},
                                         {"status", msg::mission_status_name(m.progress.status)},
                                         {"reason", m.progress.reason},
                                         {"sent_ns", m.sent_ns}};
    missions += (missions.empty() ? "\n  " : ",\n  ") + dump(mission);
  }
  nlohmann::ordered_json homes = nlohmann::ordered_json::object();
  for (const auto& [id, p] : record.homes) homes[id] = {p.x, p.y};
  return std::string("{\"format\": \"") + kFormat + "\", \"version\": " + std::to_string(kVersion) +
         ",\n \"goals\": [" + goals + (goals.empty() ? "" : "\n ") + "],\n \"missions\": [" + missions +
         (missions.empty() ? "" : "\n ") + "],\n \"homes\": " + dump(homes) + "}\n";
}

std::vector<StoredGoal> goals_to_resume(const GoalRecord& record) {
  std::vector<StoredGoal> out;
  for (const auto& [id, g] : record.goals)
    if (!g.finished) out.push_back(g);
  std::stable_sort(out.begin(), out.end(), [](const StoredGoal& a, const StoredGoal& b) {
    if (a.sent_ns != b.sent_ns) return a.sent_ns < b.sent_ns;
    return a.robot_id == kAllRobots && b.robot_id != kAllRobots;
  });
  return out;
}

std::vector<StoredMission> missions_to_resume(const GoalRecord& record) {
  std::vector<StoredMission> out;
  for (const auto& [id, m] : record.missions)
    if (m.progress.status == MissionStatus::Active) out.push_back(m);
  std::stable_sort(out.begin(), out.end(),
                   [](const StoredMission& a, const StoredMission& b) { return a.sent_ns < b.sent_ns; });
  return out;
}

Result<GoalStore> GoalStore::open(const std::string& path) {
  GoalStore store;
  store.path_ = path;
  if (path.empty()) return store;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) return Error{"goal store " + path + ": cannot be read"};
    return store;
  }
  std::ostringstream text;
  text << in.rdbuf();
  auto record = parse_goal_record(text.str());
  if (!record) return Error{"goal store " + path + ": " + record.message() + " (fix the file or delete it)"};
  store.record_ = std::move(*record);
  return store;
}

bool GoalStore::is_stale(const std::string& robot_id, int64_t sent_ns) const {
  const auto goal = record_.goals.find(robot_id);
  if (goal != record_.goals.end() && sent_ns <= goal->second.sent_ns) return true;
  const auto mission = record_.missions.find(robot_id);
  return mission != record_.missions.end() && sent_ns <= mission->second.sent_ns;
}

void GoalStore::put(const StoredGoal& goal) {
  record_.goals[goal.robot_id] = goal;
  for (auto& [id, m] : record_.missions) {
    if ((goal.robot_id == kAllRobots || id == goal.robot_id) && m.progress.status == MissionStatus::Active) {
      m.progress.status = MissionStatus::Cancelled;
      m.progress.reason = "replaced by a goal";
    }
  }
  dirty_ = true;
}

void GoalStore::put_mission(const StoredMission& mission) {
  const auto kept = record_.missions.find(mission.robot_id);
  const bool is_new =
      kept == record_.missions.end() || kept->second.mission.mission_id != mission.mission.mission_id;
  if (const auto goal = record_.goals.find(mission.robot_id); is_new && goal != record_.goals.end())
    goal->second.finished = true;
  record_.missions[mission.robot_id] = mission;
  dirty_ = true;
}

void GoalStore::finish(const std::string& robot_id, uint64_t goal_id) {
  const auto it = record_.goals.find(robot_id);
  if (it == record_.goals.end() || it->second.goal.goal_id != goal_id || it->second.finished) return;
  it->second.finished = true;
  dirty_ = true;
  // A fleet-wide goal ends when no robot that took it is still working on it, so a finished
  // exploration is not started again after a restart.
  const auto fleet = record_.goals.find(kAllRobots);
  if (robot_id == kAllRobots || fleet == record_.goals.end() || fleet->second.finished ||
      fleet->second.goal.goal_id != goal_id)
    return;
  for (const auto& [id, g] : record_.goals)
    if (id != kAllRobots && g.goal.goal_id == goal_id && !g.finished) return;
  fleet->second.finished = true;
}

void GoalStore::forget(const std::string& robot_id) {
  if (record_.goals.erase(robot_id) + record_.homes.erase(robot_id) + record_.missions.erase(robot_id) > 0)
    dirty_ = true;
}

void GoalStore::put_home(const std::string& robot_id, Vec2 home) {
  if (record_.homes.emplace(robot_id, home).second) dirty_ = true;
}

Status GoalStore::flush() {
  if (!dirty_ || path_.empty()) {
    dirty_ = false;
    return Status::ok();
  }
  const std::filesystem::path target(path_);
  std::error_code ec;
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), ec);
  const std::string temporary = path_ + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << format_goal_record(record_);
    out.flush();
    if (!out) return Error{"goal store " + temporary + ": cannot be written"};
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) return Error{"goal store " + path_ + ": " + ec.message()};
  dirty_ = false;
  return Status::ok();
}

}  // namespace slam::planner

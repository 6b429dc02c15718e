// Operator goals and path queries in JSON (see operator_requests.hpp).
#include "bridge/core/operator_requests.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

namespace slam::bridge {
namespace {

using nlohmann::json;

Result<json> parse_object(std::string_view text, const char* what) {
  json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return Error{std::string(what) + " is not a JSON object"};
  return j;
}

Result<double> finite_number(const json& j, const char* key, const char* what) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return Error{std::string(what) + " needs a number '" + key + "'"};
  const double v = it->get<double>();
  if (!std::isfinite(v)) return Error{std::string(what) + " '" + key + "' is not finite"};
  return v;
}

Result<Vec2> point(const json& j, const char* key, const char* what) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_object())
    return Error{std::string(what) + " needs an object '" + key + "' {x, y}"};
  auto x = finite_number(*it, "x", what);
  if (!x) return x.error();
  auto y = finite_number(*it, "y", what);
  if (!y) return y.error();
  return Vec2{*x, *y};
}

}  // namespace

Result<GoalCommand> parse_goal(std::string_view json_text) {
  auto j = parse_object(json_text, "goal");
  if (!j) return j.error();
  GoalCommand goal;
  const auto id = j->find("robot_id");
  if (id == j->end() || !id->is_string() || id->get<std::string>().empty())
    return Error{"goal needs a non-empty string 'robot_id'"};
  goal.robot_id = id->get<std::string>();
  if (goal.robot_id.size() > 64) return Error{"goal 'robot_id' is longer than 64 bytes"};
  if (const auto mode = j->find("mode"); mode != j->end()) {
    const auto kind = msg::parse_goal_mode(mode->is_string() ? mode->get<std::string>() : "");
    if (!kind || *kind == msg::GoalMode::Square)
      return Error{"goal 'mode' must be planned, direct, explore, home, stop or idle"};
    goal.mode = *kind;
  }
  if (goal.mode == msg::GoalMode::Planned || goal.mode == msg::GoalMode::Direct) {
    auto x = finite_number(*j, "x", "goal");
    if (!x) return x.error();
    auto y = finite_number(*j, "y", "goal");
    if (!y) return y.error();
    goal.target = {*x, *y};
  }
  return goal;
}

Result<PathQuery> parse_path_query(std::string_view json_text) {
  auto j = parse_object(json_text, "path request");
  if (!j) return j.error();
  PathQuery q;
  auto start = point(*j, "start", "path request");
  if (!start) return start.error();
  auto goal = point(*j, "goal", "path request");
  if (!goal) return goal.error();
  q.start = *start;
  q.goal = *goal;
  if (const auto a = j->find("algorithm"); a != j->end()) {
    if (!a->is_string() || a->get<std::string>().empty() || a->get<std::string>().size() > 32)
      return Error{"path request 'algorithm' must be a planner name (astar, rrtconnect, rrtstar, prmstar)"};
    q.algorithm = a->get<std::string>();
  }
  if (j->contains("time_budget_s")) {
    auto budget = finite_number(*j, "time_budget_s", "path request");
    if (!budget) return budget.error();
    if (*budget <= 0.0) return Error{"path request 'time_budget_s' must be positive"};
    q.time_budget_s = *budget;
  }
  return q;
}

std::string path_answer_json(const msg::PathReply& answer) {
  json path = json::array();
  for (const Vec2& p : answer.path) path.push_back({{"x", p.x}, {"y", p.y}});
  return json{{"status", msg::plan_status_id(answer.status)},
              {"reason", answer.reason},
              {"path", std::move(path)},
              {"length_m", answer.length_m},
              {"planning_time_s", answer.planning_time_s}}
      .dump();
}

}  // namespace slam::bridge

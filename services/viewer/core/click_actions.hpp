#pragma once
// What a click on the map means (Clicks tab: per mouse button nothing / set target / obstruct /
// unobstruct), turned into the command it sends. Real clicks and the --click test hook share it.
#include <optional>
#include <string>
#include <string_view>

#include "common/core/result.hpp"
#include "viewer/core/commands.hpp"

namespace slam::viewer {

enum class ClickAction : uint8_t { Nothing, SetTarget, Obstruct, Unobstruct };

inline constexpr const char* kClickActionNames[] = {"nothing", "target", "obstruct", "unobstruct"};
const char* click_action_name(ClickAction a);
Result<ClickAction> parse_click_action(std::string_view name);

struct ClickOutcome {
  std::optional<GoalCommand> goal;
  std::optional<MapEditCommand> edit;
};

// robot_id: the robot the goal is for ("*" = all); mode: its goal mode (idle and the modes that
// take no target become direct, since a click names a target).
ClickOutcome click_outcome(ClickAction action, Vec2 world, const std::string& robot_id, GoalMode mode,
                           double square_size, bool square_centred);

}  // namespace slam::viewer

// Click → command mapping (see click_actions.hpp).
#include "viewer/core/click_actions.hpp"

namespace slam::viewer {

const char* click_action_name(ClickAction a) {
  return kClickActionNames[static_cast<int>(a)];
}

Result<ClickAction> parse_click_action(std::string_view name) {
  for (int i = 0; i < 4; ++i)
    if (name == kClickActionNames[i]) return static_cast<ClickAction>(i);
  return Error{"unknown click action '" + std::string(name) + "' (nothing, target, obstruct, unobstruct)"};
}

ClickOutcome click_outcome(ClickAction action, Vec2 world, const std::string& robot_id, GoalMode mode,
                           double square_size, bool square_centred) {
  ClickOutcome out;
  switch (action) {
    case ClickAction::Nothing:
      break;
    case ClickAction::SetTarget: {
      const bool takes_target =
          mode == GoalMode::Direct || mode == GoalMode::Planned || mode == GoalMode::Square;
      out.goal =
          GoalCommand{robot_id, takes_target ? mode : GoalMode::Direct, world, square_size, square_centred};
      break;
    }
    case ClickAction::Obstruct:
      out.edit = MapEditCommand{MapEditKind::Obstruct, world, {}};
      break;
    case ClickAction::Unobstruct:
      out.edit = MapEditCommand{MapEditKind::Unobstruct, world, {}};
      break;
  }
  return out;
}

}  // namespace slam::viewer

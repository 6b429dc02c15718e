#pragma once
// slamctl's text side, plain C++: parsing mode/kind names from the command line and formatting
// samples as the lines a person reads. No DDS entities here, only the generated value types.
#include <optional>
#include <string>
#include <string_view>

#include "common/fastdds/fast_topics.hpp"

namespace slam::ctl {

std::optional<GoalMode> parse_goal_mode(std::string_view name);  // "planned", "explore", ...
std::string goal_mode_name(GoalMode mode);
std::string goal_status_name(GoalStatus status);
std::string plan_status_name(PlanStatus status);
std::string map_result_name(MapResult result);
std::string correction_source_name(CorrectionSource source);

// Seconds since a *_ns stamp, for "last seen 1.2 s ago".
double age_s(int64_t stamp_ns, int64_t now_ns);

std::string format_heartbeat(const Heartbeat& hb, int64_t now_ns);
// "(x, y, theta deg) version V keyframes K loops L SOURCE": a robot's map <- odom correction.
std::string format_correction(const PoseCorrection& c);
// One line per robot: its state (pose in the map frame), its goal and its correction ("-" when none
// is known: the gateway then uses the identity).
std::string format_robot(const RobotState& state, const PoseCorrection* correction, const RobotPath* path,
                         int64_t now_ns);
std::string format_path_reply(const PathReply& reply);

// One line per sample for `slamctl echo TOPIC`; long sequences are summarised.
std::string describe(const RobotObservation& s);
std::string describe(const RobotState& s);
std::string describe(const RobotOdometry& s);
std::string describe(const PoseCorrection& s);
std::string describe(const InitialPose& s);
std::string describe(const GridSnapshot& s);
std::string describe(const GridTiles& s);
std::string describe(const RobotPath& s);
std::string describe(const WaypointCommand& s);
std::string describe(const NavGoal& s);
std::string describe(const MqttTraffic& s);
std::string describe(const SimGroundTruth& s);
std::string describe(const Heartbeat& s);
std::string describe(const MapReply& s);
std::string describe(const PathReply& s);

}  // namespace slam::ctl

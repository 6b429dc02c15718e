#pragma once
// slam-simulator --play: recorded robot logs played to the broker as v2 robots speak, through the
// simulator's own robot links (one MQTT connection per robot, last will, status). Each piece of a
// log is a robot; each scan goes out as a v2 scan at its time (play_schedule.hpp) with the log's
// odometry as the robot's pose and the laser mount as the sensor offset. No world, no simulation,
// no DDS: the player prints each log's stats, its progress, and returns when everything is sent.
#include "common/core/counters.hpp"
#include "common/core/result.hpp"
#include "simulator/core/sim_options.hpp"

namespace slam::sim {

// Reads every log, connects its robots, plays them and disconnects (v2 "offline" first). An error
// when a log cannot be read or planned, or the robot links cannot be set up; a shutdown request
// stops playback early without error.
Status play_logs(const SimOptions& options, Counters& counters);

}  // namespace slam::sim

#pragma once
// Everything the gateway knows about each robot: protocol, presence, last pose, counters and the
// per-robot observation sequence. Pure and single-threaded (the gateway's loop owns it), so the
// rules for "online", "offline" and "which protocol do I answer in" are unit-tested without MQTT.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "protocol/codec_types.hpp"

namespace slam::gateway {

// Vda5050: a VDA 5050 robot (docs/protocol.md); on DDS it shows as a JSON (v2) robot.
enum class Protocol : std::uint8_t { V1, V2, Vda5050 };
// "v1", "v2", "vda5050".
std::string_view protocol_name(Protocol protocol);
enum class Presence : std::uint8_t { Online, Offline };

// Both clocks of one moment: wall time for what DDS consumers see, monotonic time for timeouts.
struct Instant {
  std::int64_t wall_ns = 0;
  std::int64_t mono_ns = 0;
};

struct RobotRecord {
  std::string id;
  Protocol protocol = Protocol::V1;  // of the latest valid message: commands go out in it
  Presence presence = Presence::Online;
  bool has_pose = false;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  bool has_heading = false;
  std::int64_t first_seen_ns = 0;  // wall clock
  std::int64_t last_seen_ns = 0;   // wall clock, last valid message
  std::int64_t last_heard_mono_ns = 0;
  std::uint64_t messages = 0;  // valid messages
  std::uint64_t points = 0;    // hits + misses over all observations
  std::uint64_t rejected = 0;  // rejected messages on this robot's topics
  std::uint64_t observation_seq = 0;
  float battery = -1.0f;  // negative: unknown
  std::string status;     // v2 robot-reported state, empty when unknown
  bool changed = true;    // not published since the last change
  bool urgent = false;    // its presence changed: published at once, not at the state period
};

struct RegistryConfig {
  std::int64_t offline_after_ns = 5'000'000'000;  // silence that turns a robot offline
  std::size_t max_robots = 10'000;                // robots beyond this are refused (bounded memory)
};

// What accepting a valid message did.
struct AcceptResult {
  enum class Kind : std::uint8_t {
    Accepted,      // counted; `seq` set for observations
    NoPose,        // a v2 points message without a pose from a robot whose pose is not known yet
    RegistryFull,  // a new robot while max_robots are known
  };
  Kind kind = Kind::Accepted;
  std::uint64_t seq = 0;      // observation sequence number (1, 2, ...), 0 for a status
  bool first_seen = false;    // the robot was not known before
  bool came_online = false;   // it was offline before this message
  bool went_offline = false;  // a status carrying the last will turned it offline
};

class RobotRegistry {
 public:
  explicit RobotRegistry(RegistryConfig config = {});

  // A valid observation. A points message without a pose (has_pose false) gets the robot's last
  // pose filled in, or NoPose when there is none. Counts the message and its points, sets the
  // protocol and marks the robot online. On NoPose/RegistryFull nothing is recorded.
  AcceptResult accept_observation(std::string_view id, Protocol protocol,
                                  protocol::DecodedObservation& observation, Instant now);
  // A valid v2 status (or a VDA 5050 state or connection without a pose): battery and state; the last
  // will ({"state":"offline"}) turns it offline.
  AcceptResult accept_status(std::string_view id, const protocol::DecodedStatus& status, Instant now,
                             Protocol protocol = Protocol::V2);
  // Battery and state reported beside a pose (a VDA 5050 state), on a known robot; not a message of its own.
  void set_status(std::string_view id, const protocol::DecodedStatus& status);
  // A rejected message on a robot's topic: counted only for robots already known (an unknown id
  // must not create a robot, or a flood of bad ids would grow the registry).
  void count_rejected(std::string_view id);

  // Turns robots silent for longer than offline_after offline; `on_offline` is called for each.
  void expire(Instant now, const std::function<void(const RobotRecord&)>& on_offline = {});
  // Marks a known robot changed, so its state is published again (its correction moved); an
  // unknown robot has nothing to publish until it speaks.
  void mark_changed(std::string_view id);
  // Calls `fn` for every robot changed since the last call (only the urgent ones: whose presence
  // changed) and clears their flags.
  void take_changed(const std::function<void(const RobotRecord&)>& fn, bool urgent_only = false);

  // Calls `fn` for every robot (in no particular order).
  void for_each(const std::function<void(const RobotRecord&)>& fn) const;

  // The operator forgot the robot: its record goes (a message from it later makes it new again).
  // False when it was not known.
  bool forget(std::string_view id);

  const RobotRecord* find(std::string_view id) const;
  std::optional<Protocol> protocol_of(std::string_view id) const;
  std::size_t size() const { return robots_.size(); }
  std::size_t online() const { return online_; }

 private:
  // Heterogeneous lookup: a string_view from the MQTT topic finds its robot without allocating.
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  RobotRecord* lookup(std::string_view id);
  // The robot's record (created on first sight), or nullptr when it is new and the registry full.
  RobotRecord* touch(std::string_view id, Protocol protocol, Instant now, AcceptResult& result);
  void set_presence(RobotRecord& r, Presence presence, AcceptResult& result);

  RegistryConfig config_;
  std::unordered_map<std::string, RobotRecord, Hash, std::equal_to<>> robots_;
  std::size_t online_ = 0;
};

}  // namespace slam::gateway

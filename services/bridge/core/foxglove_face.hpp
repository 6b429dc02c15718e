#pragma once
// The bridge's Foxglove face: every WebSocket client's session (serverInfo, the advertised channels
// and the path service, its subscriptions and the channels it advertises to publish on), and what
// goes out when (each channel only when it has news, a subscriber, and its period has passed).
// Plain C++: the WebSocket edge hands in each client's frames and sends what this returns through
// FrameSink; goals and path calls leave through OperatorSink. The ROS 2 face (ros_face.hpp) sits
// beside this one and reads the same FleetModel and MapView.
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bridge/core/bridge_options.hpp"
#include "bridge/core/fleet_model.hpp"
#include "bridge/core/foxglove_protocol.hpp"
#include "bridge/core/map_view.hpp"
#include "bridge/core/operator_requests.hpp"
#include "common/core/counters.hpp"

namespace slam::bridge {

using ClientId = uint64_t;

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  virtual void send_text(ClientId client, const std::string& text) = 0;
  // Data messages: the edge may drop one for a client that is far behind (counted there).
  virtual void send_binary(ClientId client, const std::string& bytes) = 0;
};

// A path service call waiting for the planner.
struct PathCall {
  ClientId client = 0;
  uint32_t service_id = 0;
  uint32_t call_id = 0;
  PathQuery query;
};

class OperatorSink {
 public:
  virtual ~OperatorSink() = default;
  virtual void send_goal(const GoalCommand& goal) = 0;
  // The answer comes back through FoxgloveFace::answer().
  virtual void request_path(const PathCall& call) = 0;
};

// The channels, by their advertised id.
enum class Channel : uint32_t {
  Map = 1,         // foxglove.Grid: the whole grid
  MapUpdates = 2,  // foxglove.Grid: the region changed since the last map message
  Robots = 3,      // foxglove.SceneUpdate
  Transforms = 4,  // foxglove.FrameTransforms: map -> each robot
  Paths = 5,       // foxglove.SceneUpdate: paths and targets
  Points = 6,      // foxglove.PointCloud: recent measurement points
  Health = 7,      // slam.ServiceHealth
  Alerts = 8,      // slam.Alerts: every alert, active or cleared
  RosMap = 9,      // nav_msgs/msg/OccupancyGrid (cdr, ros2msg): the whole grid, for ROS-minded layouts
};

// The topic a client advertises to publish goals on (JSON, see operator_requests.hpp).
inline constexpr const char* kGoalTopic = "/goal";
// The path service's name.
inline constexpr const char* kPathService = "/plan_path";
inline constexpr uint32_t kPathServiceId = 1;

// The advertised channels, in id order.
const std::vector<foxglove::ChannelInfo>& channel_table();

class FoxgloveFace {
 public:
  // A changed region larger than this share of the grid is not sent on /map/updates: it waits for
  // the next whole grid (at most map_full_s away). A fleet exploring all over the map changes tiles
  // everywhere, and their bounding box is then nearly the whole grid: sent every map_updates_s it
  // cost the bridge more than everything else together (docs/performance.md, Bridge).
  static constexpr double kMaxUpdateShare = 0.25;

  FoxgloveFace(const ChannelPeriods& periods, std::string session_id, FrameSink& frames,
               OperatorSink& operators, Counters& counters);

  // A client connected: serverInfo, the channels and the path service go to it.
  void connect(ClientId client);
  void disconnect(ClientId client);
  // A client's text frame (JSON op) or binary frame. Bad input is answered with a status message.
  void receive_text(ClientId client, std::string_view text);
  void receive_binary(ClientId client, std::string_view bytes);
  // The planner's answer to a call from request_path(), or nothing when it did not answer in time.
  void answer(const PathCall& call, const std::optional<msg::PathReply>& answer);

  // Sends every channel that is due: subscribed, changed since its last message and its period
  // passed. `now_mono_ns` paces, `stamp_ns` (Unix epoch) stamps the messages.
  void publish(const FleetModel& fleet, MapView& map, int64_t now_mono_ns, int64_t stamp_ns);

  size_t clients() const { return clients_.size(); }

 private:
  struct ClientChannel {
    std::string topic;
    std::string encoding;
  };
  struct Session {
    std::map<uint32_t, Channel> subscriptions;     // by subscription id
    std::map<uint32_t, ClientChannel> advertised;  // the client's own channels, by id
  };
  struct ChannelState {
    int64_t period_ns = 0;
    int64_t sent_ns = std::numeric_limits<int64_t>::min();
    std::optional<uint64_t> sent_version;
    std::string last_payload;  // for a new subscriber, sent at once
    int64_t last_stamp_ns = 0;
  };

  void handle_op(ClientId client, Session& session, std::string_view text);
  void warn(ClientId client, const std::string& message);
  bool subscribed(Channel channel) const;
  bool due(Channel channel, uint64_t version, int64_t now_mono_ns) const;
  void send(Channel channel, std::string payload, int64_t now_mono_ns, int64_t stamp_ns, uint64_t version);
  void on_client_message(ClientId client, Session& session, const foxglove::ClientMessageData& m);
  void on_service_call(ClientId client, const foxglove::ServiceCallRequest& r);

  std::string session_id_;
  FrameSink& frames_;
  OperatorSink& operators_;
  std::map<ClientId, Session> clients_;
  std::map<Channel, ChannelState> channels_;
  std::atomic<int64_t>& clients_counter_;
  std::atomic<int64_t>& messages_sent_;
  std::atomic<int64_t>& goals_received_;
  std::atomic<int64_t>& path_calls_;
  std::atomic<int64_t>& client_errors_;
};

}  // namespace slam::bridge

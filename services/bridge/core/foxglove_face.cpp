// The Foxglove face (see foxglove_face.hpp).
#include "bridge/core/foxglove_face.hpp"

#include <nlohmann/json.hpp>

#include "bridge/core/foxglove_messages.hpp"
#include "bridge/core/ros_cdr.hpp"
#include "bridge/core/schemas.hpp"

namespace slam::bridge {
namespace {

using nlohmann::json;

foxglove::ChannelInfo channel(Channel id, const char* topic, const char* schema_name, const char* schema) {
  return {static_cast<uint32_t>(id), topic, "json", schema_name, schema, "jsonschema"};
}

int64_t to_ns(double seconds) {
  return static_cast<int64_t>(seconds * 1e9);
}

}  // namespace

const std::vector<foxglove::ChannelInfo>& channel_table() {
  static const std::vector<foxglove::ChannelInfo> table = {
      channel(Channel::Map, "/map", "foxglove.Grid", schemas::kGrid),
      channel(Channel::MapUpdates, "/map/updates", "foxglove.Grid", schemas::kGrid),
      channel(Channel::Robots, "/robots", "foxglove.SceneUpdate", schemas::kSceneUpdate),
      channel(Channel::Transforms, "/tf", "foxglove.FrameTransforms", schemas::kFrameTransforms),
      channel(Channel::Paths, "/paths", "foxglove.SceneUpdate", schemas::kSceneUpdate),
      channel(Channel::Points, "/points", "foxglove.PointCloud", schemas::kPointCloud),
      channel(Channel::Health, "/health", "slam.ServiceHealth", schemas::kServiceHealth),
      channel(Channel::Alerts, "/alerts", "slam.Alerts", schemas::kAlerts),
      {static_cast<uint32_t>(Channel::RosMap), "/ros/map", "cdr", kOccupancyGridType,
       kOccupancyGridDefinition, "ros2msg"}};
  return table;
}

FoxgloveFace::FoxgloveFace(const ChannelPeriods& periods, std::string session_id, FrameSink& frames,
                           OperatorSink& operators, Counters& counters)
    : session_id_(std::move(session_id)),
      frames_(frames),
      operators_(operators),
      clients_counter_(counters.get("clients")),
      messages_sent_(counters.get("messages_sent")),
      goals_received_(counters.get("goals_received")),
      path_calls_(counters.get("path_calls")),
      client_errors_(counters.get("client_errors")) {
  channels_[Channel::Map].period_ns = to_ns(periods.map_full_s);
  channels_[Channel::MapUpdates].period_ns = to_ns(periods.map_updates_s);
  channels_[Channel::Robots].period_ns = to_ns(periods.robots_s);
  channels_[Channel::Transforms].period_ns = to_ns(periods.robots_s);
  channels_[Channel::Paths].period_ns = to_ns(periods.paths_s);
  channels_[Channel::Points].period_ns = to_ns(periods.points_s);
  channels_[Channel::Health].period_ns = to_ns(periods.health_s);
  channels_[Channel::Alerts].period_ns = to_ns(periods.health_s);
  channels_[Channel::RosMap].period_ns = to_ns(periods.map_full_s);
}

void FoxgloveFace::connect(ClientId client) {
  clients_[client] = Session{};
  clients_counter_.store(static_cast<int64_t>(clients_.size()));
  frames_.send_text(
      client, foxglove::server_info("slam-bridge", {"clientPublish", "services"}, {"json"}, session_id_));
  frames_.send_text(client, foxglove::advertise(channel_table()));
  frames_.send_text(client, foxglove::advertise_services(
                                {{kPathServiceId, kPathService, "slam/PlanPath", "slam.PathRequest",
                                  schemas::kPathRequest, "slam.PathResponse", schemas::kPathResponse}}));
}

void FoxgloveFace::disconnect(ClientId client) {
  clients_.erase(client);
  clients_counter_.store(static_cast<int64_t>(clients_.size()));
}

void FoxgloveFace::warn(ClientId client, const std::string& message) {
  bump(client_errors_);
  frames_.send_text(client, foxglove::status(foxglove::StatusLevel::Warning, message));
}

void FoxgloveFace::receive_text(ClientId client, std::string_view text) {
  const auto it = clients_.find(client);
  if (it == clients_.end()) return;
  handle_op(client, it->second, text);
}

void FoxgloveFace::handle_op(ClientId client, Session& session, std::string_view text) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("op") || !j["op"].is_string())
    return warn(client, "not a JSON object with an 'op'");
  const std::string op = j["op"].get<std::string>();
  // Each list item is checked alone; a bad one is reported and the rest still count.
  const auto items = [&](const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_array() ? *it : json::array();
  };
  if (op == "subscribe") {
    for (const json& s : items("subscriptions")) {
      if (!s.is_object() || !s.contains("id") || !s.contains("channelId") || !s["id"].is_number_unsigned() ||
          !s["channelId"].is_number_unsigned()) {
        warn(client, "subscribe: each subscription needs an unsigned id and channelId");
        continue;
      }
      const auto channel = static_cast<Channel>(s["channelId"].get<uint32_t>());
      const auto state = channels_.find(channel);
      if (state == channels_.end()) {
        warn(client, "subscribe: no channel " + std::to_string(s["channelId"].get<uint32_t>()));
        continue;
      }
      const auto sub_id = s["id"].get<uint32_t>();
      session.subscriptions[sub_id] = channel;
      if (!state->second.last_payload.empty()) {
        frames_.send_binary(client,
                            foxglove::message_data(sub_id, static_cast<uint64_t>(state->second.last_stamp_ns),
                                                   state->second.last_payload));
        bump(messages_sent_);
      }
    }
  } else if (op == "unsubscribe") {
    for (const json& id : items("subscriptionIds"))
      if (id.is_number_unsigned()) session.subscriptions.erase(id.get<uint32_t>());
  } else if (op == "advertise") {
    for (const json& c : items("channels")) {
      if (!c.is_object() || !c.contains("id") || !c["id"].is_number_unsigned() || !c.contains("topic") ||
          !c["topic"].is_string()) {
        warn(client, "advertise: each channel needs an unsigned id and a topic");
        continue;
      }
      const std::string encoding =
          c.contains("encoding") && c["encoding"].is_string() ? c["encoding"].get<std::string>() : "";
      session.advertised[c["id"].get<uint32_t>()] = {c["topic"].get<std::string>(), encoding};
    }
  } else if (op == "unadvertise") {
    for (const json& id : items("channelIds"))
      if (id.is_number_unsigned()) session.advertised.erase(id.get<uint32_t>());
  } else {
    warn(client, "unsupported op '" + op + "'");
  }
}

void FoxgloveFace::receive_binary(ClientId client, std::string_view bytes) {
  const auto it = clients_.find(client);
  if (it == clients_.end()) return;
  auto frame = foxglove::parse_client_binary(bytes);
  if (!frame) return warn(client, frame.message());
  if (const auto* m = std::get_if<foxglove::ClientMessageData>(&*frame))
    on_client_message(client, it->second, *m);
  else
    on_service_call(client, std::get<foxglove::ServiceCallRequest>(*frame));
}

void FoxgloveFace::on_client_message(ClientId client, Session& session,
                                     const foxglove::ClientMessageData& m) {
  const auto channel = session.advertised.find(m.channel_id);
  if (channel == session.advertised.end())
    return warn(client, "message on channel " + std::to_string(m.channel_id) + ", which was not advertised");
  if (channel->second.topic != kGoalTopic || channel->second.encoding != "json")
    return warn(client,
                "only " + std::string(kGoalTopic) + " (json) is accepted, not " + channel->second.topic);
  auto goal = parse_goal(m.payload);
  if (!goal) return warn(client, goal.message());
  bump(goals_received_);
  operators_.send_goal(*goal);
}

void FoxgloveFace::on_service_call(ClientId client, const foxglove::ServiceCallRequest& r) {
  const auto fail = [&](const std::string& message) {
    bump(client_errors_);
    frames_.send_text(client, foxglove::service_call_failure(r.service_id, r.call_id, message));
  };
  if (r.service_id != kPathServiceId) return fail("no service " + std::to_string(r.service_id));
  if (r.encoding != "json") return fail("the path service takes json, not " + std::string(r.encoding));
  auto query = parse_path_query(r.payload);
  if (!query) return fail(query.message());
  bump(path_calls_);
  operators_.request_path(PathCall{client, r.service_id, r.call_id, *query});
}

void FoxgloveFace::answer(const PathCall& call, const std::optional<msg::PathReply>& answer) {
  if (!clients_.contains(call.client)) return;  // gone meanwhile
  if (!answer) {
    frames_.send_text(call.client, foxglove::service_call_failure(call.service_id, call.call_id,
                                                                  "no planner answered in time"));
    return;
  }
  frames_.send_binary(call.client, foxglove::service_call_response(call.service_id, call.call_id, "json",
                                                                   path_answer_json(*answer)));
}

bool FoxgloveFace::subscribed(Channel channel) const {
  for (const auto& [id, session] : clients_)
    for (const auto& [sub, c] : session.subscriptions)
      if (c == channel) return true;
  return false;
}

bool FoxgloveFace::due(Channel channel, uint64_t version, int64_t now_mono_ns) const {
  const ChannelState& s = channels_.at(channel);
  if (s.sent_version == version) return false;
  if (s.sent_ns != std::numeric_limits<int64_t>::min() && now_mono_ns - s.sent_ns < s.period_ns) return false;
  return subscribed(channel);
}

void FoxgloveFace::send(Channel channel, std::string payload, int64_t now_mono_ns, int64_t stamp_ns,
                        uint64_t version) {
  ChannelState& s = channels_.at(channel);
  s.sent_ns = now_mono_ns;
  s.sent_version = version;
  s.last_stamp_ns = stamp_ns;
  s.last_payload = std::move(payload);
  for (const auto& [client, session] : clients_)
    for (const auto& [sub, c] : session.subscriptions)
      if (c == channel) {
        frames_.send_binary(client,
                            foxglove::message_data(sub, static_cast<uint64_t>(stamp_ns), s.last_payload));
        bump(messages_sent_);
      }
}

void FoxgloveFace::publish(const FleetModel& fleet, MapView& map, int64_t now_mono_ns, int64_t stamp_ns) {
  const FleetVersions& v = fleet.versions();
  if (map.has_grid()) {
    if (due(Channel::Map, map.revision(), now_mono_ns)) {
      map.take_changed();  // the whole grid covers every change so far
      const GridGeometry& g = map.geometry();
      send(Channel::Map, grid_message(g, map.cells(), CellBox{0, 0, g.width, g.height}, map.stamp_ns()),
           now_mono_ns, stamp_ns, map.revision());
    } else if (static_cast<double>(map.changed().cells()) <=
                   kMaxUpdateShare * static_cast<double>(map.geometry().cells()) &&
               due(Channel::MapUpdates, map.revision(), now_mono_ns)) {
      const CellBox changed = map.take_changed();
      if (!changed.empty())
        send(Channel::MapUpdates, grid_message(map.geometry(), map.cells(), changed, map.stamp_ns()),
             now_mono_ns, stamp_ns, map.revision());
    }
    if (due(Channel::RosMap, map.revision(), now_mono_ns))
      send(Channel::RosMap, occupancy_grid_cdr(occupancy_grid(map.geometry(), map.cells(), map.stamp_ns())),
           now_mono_ns, stamp_ns, map.revision());
  }
  if (due(Channel::Robots, v.robots, now_mono_ns))
    send(Channel::Robots, robots_message(fleet, stamp_ns), now_mono_ns, stamp_ns, v.robots);
  if (due(Channel::Transforms, v.robots, now_mono_ns))
    send(Channel::Transforms, transforms_message(fleet, stamp_ns), now_mono_ns, stamp_ns, v.robots);
  if (due(Channel::Paths, v.paths, now_mono_ns))
    send(Channel::Paths, paths_message(fleet, stamp_ns), now_mono_ns, stamp_ns, v.paths);
  if (due(Channel::Points, v.points, now_mono_ns))
    send(Channel::Points, points_message(fleet, stamp_ns), now_mono_ns, stamp_ns, v.points);
  if (due(Channel::Alerts, v.alerts, now_mono_ns))
    send(Channel::Alerts, alerts_message(fleet, stamp_ns), now_mono_ns, stamp_ns, v.alerts);
  // Health changes with time alone (seconds since each service was heard).
  const auto health_version = static_cast<uint64_t>(now_mono_ns);
  if (!fleet.services().empty() && due(Channel::Health, health_version, now_mono_ns))
    send(Channel::Health, health_message(fleet, now_mono_ns, stamp_ns), now_mono_ns, stamp_ns,
         health_version);
}

}  // namespace slam::bridge

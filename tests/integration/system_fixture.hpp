#pragma once
// What system_test.cpp drives the whole fleet with: a room scene a legacy robot reports in v1 bytes,
// a paho robot that keeps reporting through broker restarts, and a DDS probe that rebuilds the map
// and watches heartbeats. Header-only: one test program uses it.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "inbox.hpp"
#include "mqtt_test_client.hpp"
#include "observation_batches.hpp"
#include "received_map.hpp"

namespace slam::system_test {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

struct Vec {
  double x = 0.0;
  double y = 0.0;
};

inline double distance(Vec a, Vec b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

inline double point_segment_distance(Vec p, Vec a, Vec b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return distance(p, Vec{a.x + t * dx, a.y + t * dy});
}

inline double cross(Vec o, Vec a, Vec b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Shortest distance between segments ab and cd; 0 when they cross.
inline double segment_distance(Vec a, Vec b, Vec c, Vec d) {
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({point_segment_distance(a, c, d), point_segment_distance(b, c, d),
                   point_segment_distance(c, a, b), point_segment_distance(d, a, b)});
}

// v1 adv payload: int16 LE pairs in centimetres, the position first.
inline std::string v1_adv(Vec position, const std::vector<Vec>& points = {}) {
  std::string out;
  const auto put = [&out](double metres) {
    const auto v = static_cast<uint16_t>(static_cast<int16_t>(std::lround(metres * 100.0)));
    out += static_cast<char>(v & 0xff);
    out += static_cast<char>(v >> 8);
  };
  put(position.x);
  put(position.y);
  for (const Vec& p : points) {
    put(p.x);
    put(p.y);
  }
  return out;
}

// A v1 command (exactly 4 bytes) in metres.
inline std::optional<Vec> v1_cmd(const std::string& bytes) {
  if (bytes.size() != 4) return std::nullopt;
  const auto at = [&bytes](size_t i) {
    const auto u =
        static_cast<uint16_t>(static_cast<uint8_t>(bytes[i]) | (static_cast<uint8_t>(bytes[i + 1]) << 8));
    return static_cast<int16_t>(u) / 100.0;
  };
  return Vec{at(0), at(2)};
}

inline std::string from_hex(const std::string& hex) {
  std::string out;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    out += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
  return out;
}

// A room x -1..5 m, y -3..3 m with a wall at x = 1.52 m, y -0.6..0.6 m between the start (0, 0)
// and the goal (3, 0). v1 carries no free space, so the robot surveys from (0, 2) and (0, -2) before
// it settles at the start: the rays to the room's far walls map the space around and behind the wall.
// Points sit 2 cm inside 5 cm cells so no hit lands on a cell boundary.
struct Scene {
  static constexpr Vec kStart{0.0, 0.0};
  static constexpr Vec kGoal{3.0, 0.0};
  static constexpr Vec kWallA{1.52, -0.6};
  static constexpr Vec kWallB{1.52, 0.6};
  static constexpr Vec kSurvey[2] = {{0.0, 2.0}, {0.0, -2.0}};

  static std::vector<Vec> wall() {
    std::vector<Vec> out;
    for (int cm = -57; cm <= 58; cm += 5) out.push_back(Vec{1.52, cm / 100.0});
    return out;
  }
  static std::vector<Vec> room() {
    std::vector<Vec> out;
    for (int cm = -98; cm <= 498; cm += 5) {
      out.push_back(Vec{cm / 100.0, -2.98});
      out.push_back(Vec{cm / 100.0, 2.98});
    }
    for (int cm = -293; cm <= 293; cm += 5) {
      out.push_back(Vec{-0.98, cm / 100.0});
      out.push_back(Vec{4.98, cm / 100.0});
    }
    return out;
  }
  // Room points a robot at `from` sees past the wall (rays keep 15 cm off it), plus the wall from the start.
  static std::vector<Vec> seen_from(Vec from) {
    std::vector<Vec> out;
    for (const Vec& p : room())
      if (segment_distance(from, p, kWallA, kWallB) >= 0.15) out.push_back(p);
    if (distance(from, kStart) < 1e-9) {
      const auto w = wall();
      out.insert(out.end(), w.begin(), w.end());
    }
    return out;
  }
};

using testkit::Inbox;

using Map = testkit::ReceivedMap;

template <class T>
T take(Result<T> r) {
  if (!r) throw std::runtime_error(r.message());
  return std::move(*r);
}

// The test's DDS side: the map, observations, robot states and heartbeats, and the operator's goals.
class Probe {
 public:
  explicit Probe(int domain) {
    participant_ = take(dds::Participant::create(domain, "system-test"));
    snapshot_reader_ =
        take(dds::make_reader(*participant_, dds::kGridSnapshot, [this](const GridSnapshot& s, const auto&) {
          std::lock_guard lock(mutex_);
          snapshots_.push_back(s);
        }));
    patch_reader_ =
        take(dds::make_reader(*participant_, dds::kGridTiles, [this](const GridTiles& p, const auto&) {
          std::lock_guard lock(mutex_);
          patches_.push_back(p);
        }));
    observation_reader_ = testkit::make_observation_reader(*participant_, [this](const RobotObservation& o) {
      std::lock_guard lock(mutex_);
      observed_[o.robot_id().to_string()].push_back(Clock::now());
    });
    heartbeat_reader_ =
        take(dds::make_reader(*participant_, dds::kHeartbeat, [this](const Heartbeat& h, const auto&) {
          std::lock_guard lock(mutex_);
          heartbeats_[h.service().to_string()] = h;
        }));
    goals_ = take(dds::make_writer(*participant_, dds::kNavGoal));
  }

  // The map as a receiver sees it now: the newest snapshot plus the consecutive patches after it.
  // Newest by (layout, version), not by arrival: a large snapshot of a killed mapper may arrive after
  // its successor's, and layout ids only grow.
  std::optional<Map> map() const {
    std::lock_guard lock(mutex_);
    const GridSnapshot* newest = nullptr;
    for (const GridSnapshot& s : snapshots_)
      if (!newest ||
          std::pair(s.layout_id(), s.version()) >= std::pair(newest->layout_id(), newest->version()))
        newest = &s;
    if (!newest) return std::nullopt;
    return testkit::assemble(*newest, patches_);
  }
  size_t snapshot_count() const {
    std::lock_guard lock(mutex_);
    return snapshots_.size();
  }
  // The first snapshot from index `from` on whose layout differs from `layout_id`: a restarted mapper's
  // (its layout ids start from the clock), not a large sample of the old one that was still in flight.
  std::optional<GridSnapshot> snapshot_of_another_layout(size_t from, uint32_t layout_id) const {
    std::lock_guard lock(mutex_);
    for (size_t i = from; i < snapshots_.size(); ++i)
      if (snapshots_[i].layout_id() != layout_id) return snapshots_[i];
    return std::nullopt;
  }

  // When the first observation of `robot` after `since` arrived on DDS.
  std::optional<Clock::time_point> observation_after(const std::string& robot,
                                                     Clock::time_point since) const {
    std::lock_guard lock(mutex_);
    auto it = observed_.find(robot);
    if (it == observed_.end()) return std::nullopt;
    auto at = std::upper_bound(it->second.begin(), it->second.end(), since);
    return at == it->second.end() ? std::nullopt : std::optional(*at);
  }
  // The latest heartbeat of `service` from process `pid` (any process when 0).
  std::optional<Heartbeat> heartbeat(const std::string& service, uint32_t pid = 0) const {
    std::lock_guard lock(mutex_);
    auto it = heartbeats_.find(service);
    if (it == heartbeats_.end() || (pid != 0 && it->second.pid() != pid)) return std::nullopt;
    return it->second;
  }
  int64_t counter(const std::string& service, uint32_t pid, const std::string& name) const {
    const auto hb = heartbeat(service, pid);
    if (!hb) return -1;
    for (const Counter& c : hb->counters())
      if (c.name() == name) return c.value();
    return -1;
  }
  // A standing goal held as the viewer holds it: a live transient-local writer a restarted planner reads.
  bool set_goal(const std::string& robot, GoalMode mode, Vec target) {
    NavGoal g;
    g.robot_id(robot);
    g.goal_id(++goal_id_);
    g.mode(mode);
    g.target().x(target.x);
    g.target().y(target.y);
    return goals_->write(g);
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::vector<Clock::time_point>> observed_;
  std::map<std::string, Heartbeat> heartbeats_;
  std::vector<GridSnapshot> snapshots_;
  std::vector<GridTiles> patches_;
  uint64_t goal_id_ = 100;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Reader<GridSnapshot>> snapshot_reader_;
  std::unique_ptr<dds::Reader<GridTiles>> patch_reader_;
  std::unique_ptr<dds::Reader<RobotObservationBatch>> observation_reader_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader_;
  std::unique_ptr<dds::Writer<NavGoal>> goals_;
};

// A v1 robot on paho: reports `adv` every period (QoS 0, as a radio link would), reconnects and
// re-subscribes after a broker restart, and records each command with the time it arrived.
class PahoRobot {
 public:
  PahoRobot(int port, std::string id, std::string adv, std::chrono::milliseconds period = 100ms)
      : id_(std::move(id)), adv_(std::move(adv)), period_(period), client_(port, "robot-" + id_) {
    thread_ = std::thread([this] { loop(); });
  }
  ~PahoRobot() {
    stop_ = true;
    thread_.join();
  }
  PahoRobot(const PahoRobot&) = delete;
  PahoRobot& operator=(const PahoRobot&) = delete;

  void set_adv(std::string adv) {
    std::lock_guard lock(mutex_);
    adv_ = std::move(adv);
  }
  void pause(bool paused) { paused_ = paused; }
  // Publishes `adv` once, at the next period, paused or not.
  void send_once(std::string adv) {
    std::lock_guard lock(mutex_);
    once_ = std::move(adv);
  }
  // Commands received after `since`, as (arrival, payload).
  std::vector<std::pair<Clock::time_point, std::string>> commands(Clock::time_point since = {}) const {
    std::vector<std::pair<Clock::time_point, std::string>> out;
    for (const auto& m : client_.messages())
      if (m.received_at > since) out.emplace_back(m.received_at, m.payload);
    return out;
  }

 private:
  void loop() {
    const std::string adv_topic = "v1/robot/" + id_ + "/adv";
    const std::string cmd_topic = "v1/server/" + id_ + "/cmd";
    while (!stop_) {
      if (!client_.connected() && (client_.connect() != 0 || !client_.subscribe(cmd_topic))) {
        std::this_thread::sleep_for(period_);
        continue;
      }
      std::string payload;
      {
        std::lock_guard lock(mutex_);
        if (!once_.empty())
          payload = std::exchange(once_, {});
        else if (!paused_)
          payload = adv_;
      }
      // QoS 0: a lost report is replaced by the next one, as on a robot's radio link.
      if (!payload.empty()) client_.publish(adv_topic, payload, 0);
      std::this_thread::sleep_for(period_);
    }
  }

  std::string id_;
  mutable std::mutex mutex_;
  std::string adv_;
  std::string once_;
  std::chrono::milliseconds period_;
  std::atomic<bool> paused_{false};
  std::atomic<bool> stop_{false};
  testkit::MqttTestClient client_;
  std::thread thread_;
};

}  // namespace slam::system_test

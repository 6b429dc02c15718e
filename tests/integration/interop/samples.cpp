#include "samples.hpp"

#include <array>
#include <string>

namespace slam::interop {
namespace {

Point2 point(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

Pose2 pose(double x, double y, double theta) {
  Pose2 p;
  p.x(x);
  p.y(y);
  p.theta(theta);
  return p;
}

std::vector<Point2> points(size_t n, double scale) {
  std::vector<Point2> out;
  for (size_t i = 0; i < n; ++i)
    out.push_back(point(scale * static_cast<double>(i) + 0.125, -scale * static_cast<double>(i) - 1e-9));
  return out;
}

std::vector<uint8_t> bytes(size_t n) {
  std::vector<uint8_t> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = static_cast<uint8_t>((i * 37 + 11) & 0xff);
  return out;
}

}  // namespace

RobotObservationBatch sample_robot_observations() {
  RobotObservation s;
  s.robot_id("robot-ä7");
  s.seq(123456789012ULL);
  s.stamp_ns(1763800000123456789LL);
  s.robot_stamp_ns(4321987654321LL);
  s.protocol(PROTOCOL_V2);
  s.pose(pose(1.5, -2.25, 3.0));
  s.has_heading(true);
  s.hits(points(500, 0.05));
  s.misses(points(300, -0.02));
  RobotObservation v1;
  v1.robot_id("r1");
  v1.seq(1);
  v1.protocol(PROTOCOL_V1);
  v1.pose(pose(-3, 4, 0));
  v1.hits(points(3, 0.1));
  RobotObservationBatch batch;
  batch.gateway_id("host:1234");
  batch.batch_seq(42);
  batch.observations({s, v1});
  return batch;
}

RobotState sample_robot_state() {
  RobotState s;
  s.robot_id("r2");
  s.protocol(PROTOCOL_V2);
  s.presence(PRESENCE_OFFLINE);
  s.pose(pose(-1, 2, -0.5));
  s.has_heading(true);
  s.first_seen_ns(-5);
  s.last_seen_ns(1763800000000000000LL);
  s.messages(1ULL << 40);
  s.points(77);
  s.rejected(3);
  s.battery(0.75f);
  s.status("exploring");
  return s;
}

RobotOdometry sample_robot_odometry() {
  RobotOdometry s;
  s.robot_id("robot-ö3");
  s.stamp_ns(1763800000987654321LL);
  s.odom_pose(pose(-3.5, 0.0625, 2.75));
  s.has_heading(true);
  s.correction_version((1ULL << 50) + 3);
  return s;
}

PoseCorrection sample_pose_correction() {
  PoseCorrection s;
  s.robot_id("r9");
  s.version((1ULL << 45) + 17);
  s.stamp_ns(-123456789);
  s.map_from_odom(pose(0.25, -1.75, -3.0));
  s.covariance(std::array<double, 6>{1e-4, -2e-6, 3e-7, 4e-4, -5e-8, 6e-5});
  s.segment(4);
  s.keyframes(1234567);
  s.loop_closures(89);
  s.source(CORRECTION_RESTORED);
  return s;
}

InitialPose sample_initial_pose() {
  InitialPose s;
  s.request_id(0xfedcba9876543210ULL);
  s.robot_id("legacy-07");
  s.pose(pose(12.5, -8.125, 1.0471975511965976));
  return s;
}

PlacementAnswer sample_placement_answer() {
  PlacementAnswer s;
  s.request_id(0x0123456789abcdefULL);
  s.robot_id("lidar-02");
  s.verdict(PLACEMENT_REJECT);
  return s;
}

GridSnapshot sample_grid_snapshot() {
  GridSnapshot s;
  s.layout_id(7);
  s.version(99);
  s.stamp_ns(42);
  s.info().width(400);
  s.info().height(300);
  s.info().resolution(0.05);
  s.info().origin(point(-10, -7.5));
  s.info().inflation_radius(0.2);
  s.cells(bytes(400 * 300));
  return s;
}

GridTiles sample_grid_tiles() {
  GridTiles s;
  s.layout_id(7);
  s.version(100);
  s.stamp_ns(43);
  s.tile_side(32);
  s.encoding(1);
  s.tiles({3, 17, 4000000000u});
  s.data(bytes(301));
  return s;
}

GridConfig sample_grid_config() {
  GridConfig s;
  s.request_id(5);
  s.resolution(0.1);
  s.origin(point(-3, -4));
  s.width_m(30);
  s.height_m(40);
  s.inflation_radius(0.25);
  s.legacy_mode(true);
  return s;
}

MapEdit sample_map_edit() {
  MapEdit s;
  s.request_id(9);
  s.kind(EDIT_RESET_ROBOT);
  s.point(point(1.25, 2.5));
  s.robot_id("robot-1");
  return s;
}

MapFileRequest sample_map_file_request() {
  MapFileRequest s;
  s.request_id(11);
  s.action(MAP_EXPORT_TRAJECTORY_CARMEN);
  s.yaml_path("/tmp/maps/office floor/sim-1.log");
  s.robot_id("sim-ä1");
  return s;
}

MapReply sample_map_reply() {
  MapReply s;
  s.request_id(11);
  s.result(MAP_BAD_FILE);
  s.message("map.yaml: resolution must be positive");
  return s;
}

NavGoal sample_nav_goal() {
  NavGoal s;
  s.robot_id("*");
  s.goal_id(3);
  s.mode(GOAL_SQUARE);
  s.target(point(2, 3));
  s.square_size(1.5);
  s.square_anchor(SQUARE_CENTRED);
  return s;
}

RobotPath sample_robot_path() {
  RobotPath s;
  s.robot_id("r1");
  s.goal_id(3);
  s.mode(GOAL_PLANNED);
  s.status(GOAL_STATUS_FAILED);
  s.target(point(9, 9));
  s.waypoints(points(64, 0.3));
  s.current(12);
  s.reason("goal blocked");
  return s;
}

WaypointCommand sample_waypoint_command() {
  WaypointCommand s;
  s.robot_id("r1");
  s.seq(77);
  s.waypoint(point(0.5, -0.5));
  s.remaining(points(20, 0.5));
  return s;
}

PathRequest sample_path_request() {
  PathRequest s;
  s.request_id(1234);
  s.client_id("slamctl:99");
  s.start(point(0, 0));
  s.goal(point(5, 5));
  s.algorithm("rrtconnect");
  s.time_budget_s(0.25);
  return s;
}

PathReply sample_path_reply() {
  PathReply s;
  s.request_id(1234);
  s.client_id("slamctl:99");
  s.status(PLAN_NO_PATH);
  s.reason("goal enclosed");
  s.path(points(100, 0.1));
  s.length_m(12.5);
  s.planning_time_s(0.0125);
  return s;
}

MqttTraffic sample_mqtt_traffic() {
  MqttTraffic s;
  s.seq(8);
  s.stamp_ns(1);
  s.direction(MQTT_OUTBOUND);
  s.topic("v1/server/r1/cmd");
  s.payload(bytes(1024));
  s.payload_size(4096);
  return s;
}

MqttRequest sample_mqtt_request() {
  MqttRequest s;
  s.request_id(4);
  s.kind(MQTT_UNSUBSCRIBE);
  s.topic("v1/robot/+/adv");
  s.payload(bytes(5000));
  s.qos(1);
  s.retain(true);
  return s;
}

MqttReply sample_mqtt_reply() {
  MqttReply s;
  s.request_id(0xfedcba9876543210ULL);
  s.ok(false);
  s.message("filter 'v1/#/x': '#' must be the last level (ü)");
  return s;
}

MqttSubscriptions sample_mqtt_subscriptions() {
  MqttSubscriptions s;
  s.connected(true);
  s.broker("tcp://127.0.0.1:1883");
  s.filters().push_back("v1/robot/+/adv");
  s.filters().push_back("v2/robot/#");
  s.filters().push_back("site/ä/#");
  return s;
}

SimControl sample_sim_control() {
  SimControl s;
  s.command_id(6);
  s.kind(SIM_SET_NOISE);
  s.count(3);
  s.poses().push_back(pose(1, 1, 0.5));
  s.poses().push_back(pose(2, 1, -0.5));
  s.robot_id("sim-2");
  s.world("office");
  s.range_noise_sd(0.02);
  s.dropout(0.05);
  s.odometry_drift(0.01);
  s.speed_factor(2);
  return s;
}

SimReply sample_sim_reply() {
  SimReply s;
  s.command_id(0x0123456789abcdefULL);
  s.ok(false);
  s.message("set world: no world 'maze-ü' (not built in, no such file)");
  return s;
}

SimWorld sample_sim_world() {
  SimWorld s;
  s.name("maze");
  s.width_m(20);
  s.height_m(15);
  for (int i = 0; i < 200; ++i) {
    Segment2 w;
    w.a(point(i, 0));
    w.b(point(i, 1.5 * i));
    s.walls().push_back(w);
  }
  return s;
}

SimGroundTruth sample_sim_ground_truth() {
  SimGroundTruth s;
  s.stamp_ns(99);
  s.paused(true);
  for (int i = 0; i < 50; ++i) {
    SimRobotTruth r;
    r.robot_id("sim-" + std::to_string(i));
    r.true_pose(pose(i, -i, 0.1 * i));
    r.reported_pose(pose(i + 0.01, -i, 0.1 * i));
    s.robots().push_back(r);
  }
  return s;
}

Heartbeat sample_heartbeat() {
  Heartbeat s;
  s.service("mapper");
  s.instance_id("host:123");
  s.pid(123);
  s.host("host");
  s.stamp_ns(5);
  s.uptime_s(12.5);
  s.state(SERVICE_STOPPING);
  for (int i = 0; i < 10; ++i) {
    Counter c;
    c.name("counter_" + std::to_string(i));
    c.value(-i * 1000000007LL);
    s.counters().push_back(c);
  }
  return s;
}

Alert sample_alert() {
  Alert s;
  s.alert_id("battery/sim-7");
  s.kind(ALERT_BATTERY_LOW);
  s.subject("sim-7");
  s.active(true);
  s.raised_ns(1'700'000'000'123'456'789LL);
  s.stamp_ns(-3);
  s.message("robot 'sim-7' battery 12 % (below 20 %): sent home");
  s.raised_by("host:4242");
  return s;
}

ForgetRobot sample_forget_robot() {
  ForgetRobot s;
  s.request_id(0xfedcba9876543210ULL);
  s.robot_id("forgotten-robot-1");
  return s;
}

FleetDigest sample_fleet_digest() {
  FleetDigest s;
  s.gateway_id("gateway-host:4242");
  s.stamp_ns(1763800000987654321LL);
  for (int i = 0; i < 300; ++i) {
    DigestRobot r;
    r.robot_id("robot-ü" + std::to_string(i));
    r.pose(pose(0.5 * i, -0.25 * i, 0.001 * i));
    r.has_heading(i % 2 == 0);
    r.presence(i % 3 == 0 ? PRESENCE_OFFLINE : PRESENCE_ONLINE);
    r.last_seen_ns(1763800000000000000LL + i);
    s.robots().push_back(r);
  }
  return s;
}

FleetPoints sample_fleet_points() {
  FleetPoints s;
  s.gateway_id("gateway-host:4242");
  s.stamp_ns(-7);
  for (int i = 0; i < 200; ++i) {
    DigestRobotPoints r;
    r.robot_id(std::string("r").append(std::to_string(i)));
    r.stamp_ns(1763800000000000000LL - i);
    for (int k = 0; k < i % 20; ++k) {
      DigestPoint p;
      p.x(0.125f * static_cast<float>(k) - 3.5f);
      p.y(-1e-3f * static_cast<float>(i));
      r.points().push_back(p);
    }
    s.robots().push_back(r);
  }
  return s;
}

namespace gm = geometry_msgs::msg::dds_;

namespace {

std_msgs::msg::dds_::Header_ ros_header(int32_t sec, const std::string& frame) {
  std_msgs::msg::dds_::Header_ h;
  h.stamp().sec(sec);
  h.stamp().nanosec(999'999'999u);
  h.frame_id(frame);
  return h;
}

gm::Pose_ ros_pose(double x, double y, double z) {
  gm::Pose_ p;
  p.position().x(x);
  p.position().y(y);
  p.position().z(z);
  p.orientation().x(0.1);
  p.orientation().y(-0.2);
  p.orientation().z(0.3);
  p.orientation().w(0.927);
  return p;
}

}  // namespace

nav_msgs::msg::dds_::OccupancyGrid_ sample_ros_occupancy_grid() {
  nav_msgs::msg::dds_::OccupancyGrid_ s;
  s.header(ros_header(-5, "map"));
  s.info().map_load_time().sec(1'700'000'000);
  s.info().map_load_time().nanosec(7u);
  s.info().resolution(0.05f);
  s.info().width(97);  // odd sizes: a misaligned field after the cells shows
  s.info().height(31);
  s.info().origin(ros_pose(-12.5, 3.25, 0.0));
  for (uint32_t i = 0; i < 97u * 31u; ++i)
    s.data().push_back(static_cast<int8_t>(i % 3 == 0 ? -1 : i % 3 == 1 ? 0 : 100));
  return s;
}

tf2_msgs::msg::dds_::TFMessage_ sample_ros_tf_message() {
  tf2_msgs::msg::dds_::TFMessage_ s;
  for (int i = 0; i < 5; ++i) {
    gm::TransformStamped_ t;
    t.header(ros_header(i, "map"));
    t.child_frame_id("robot-" + std::to_string(i) + "-ä");
    t.transform().translation().x(i * 1.5);
    t.transform().translation().y(-i * 0.25);
    t.transform().translation().z(0.125);
    t.transform().rotation(ros_pose(0, 0, 0).orientation());
    s.transforms().push_back(t);
  }
  return s;
}

gm::PoseStamped_ sample_ros_pose_stamped() {
  gm::PoseStamped_ s;
  s.header(ros_header(42, "map"));
  s.pose(ros_pose(4.5, -1.75, 0.0));
  return s;
}

gm::PoseWithCovarianceStamped_ sample_ros_pose_with_covariance_stamped() {
  gm::PoseWithCovarianceStamped_ s;
  s.header(ros_header(43, "map"));
  s.pose().pose(ros_pose(-0.5, 2.0, 0.0));
  for (size_t i = 0; i < 36; ++i) s.pose().covariance()[i] = 0.01 * static_cast<double>(i) - 0.1;
  return s;
}

}  // namespace slam::interop

// Writes a small ROS 2 recording as rosbag2 would (MCAP, profile "ros2", schema encoding "ros2msg",
// message encoding "cdr"), with @mcap/core and Foxglove's ROS 2 CDR serialiser, for the C++ reader
// of robot logs (tests/unit/simulator/ros2_mcap_log_test.cpp, which knows the same scenario):
// - /tf_static: base_footprint -> base_link (0.1, 0, 0.2), base_link -> laser (0.2, 0.1, 0.1, yaw 0.5);
// - /odom (nav_msgs/msg/Odometry, child base_footprint): 101 poses at 20 Hz from t = 100 s,
//   x = 0.5 (t - 100), yaw = 0.2 (t - 100);
// - /scan (sensor_msgs/msg/LaserScan, frame laser): 24 scans at 5 Hz from t = 100.01 s, five beams
//   [1, 2, inf, 0.01, 3.5] from -1 rad by 0.5 rad, range 0.05..4 m; then one stamped 101.0 s (a step
//   back), one at 110 s (no odometry near it) and two bytes that are no LaserScan;
// - /chatter (std_msgs/msg/String): one message.
// Usage: node ros2_scan_mcap_writer.mjs OUT.mcap. The file is chunked (@mcap/core's default).
import { writeFileSync } from "node:fs";
import rosmsg from "@foxglove/rosmsg";
import rosmsg2 from "@foxglove/rosmsg2-serialization";
import { McapWriter } from "@mcap/core";

const separator = "=".repeat(80);
const definitions = {
  "builtin_interfaces/Time": "int32 sec\nuint32 nanosec",
  "std_msgs/Header": "builtin_interfaces/Time stamp\nstring frame_id",
  "geometry_msgs/Vector3": "float64 x\nfloat64 y\nfloat64 z",
  "geometry_msgs/Point": "float64 x\nfloat64 y\nfloat64 z",
  "geometry_msgs/Quaternion": "float64 x\nfloat64 y\nfloat64 z\nfloat64 w",
  "geometry_msgs/Pose": "Point position\nQuaternion orientation",
  "geometry_msgs/PoseWithCovariance": "Pose pose\nfloat64[36] covariance",
  "geometry_msgs/Twist": "Vector3 linear\nVector3 angular",
  "geometry_msgs/TwistWithCovariance": "Twist twist\nfloat64[36] covariance",
  "geometry_msgs/Transform": "Vector3 translation\nQuaternion rotation",
  "geometry_msgs/TransformStamped": "std_msgs/Header header\nstring child_frame_id\nTransform transform",
};
// A message definition in rosbag2's one-text form: the type's own fields, then each dependency.
function schemaText(fields, dependencies) {
  return [fields, ...dependencies.map((d) => `${separator}\nMSG: ${d}\n${definitions[d]}`)].join("\n");
}
const types = {
  "sensor_msgs/msg/LaserScan": schemaText(
    "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n" +
      "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n" +
      "float32[] ranges\nfloat32[] intensities",
    ["std_msgs/Header", "builtin_interfaces/Time"],
  ),
  "nav_msgs/msg/Odometry": schemaText(
    "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n" +
      "geometry_msgs/TwistWithCovariance twist",
    [
      "std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose",
      "geometry_msgs/Point", "geometry_msgs/Quaternion", "geometry_msgs/TwistWithCovariance",
      "geometry_msgs/Twist", "geometry_msgs/Vector3",
    ],
  ),
  "tf2_msgs/msg/TFMessage": schemaText("geometry_msgs/TransformStamped[] transforms", [
    "geometry_msgs/TransformStamped", "std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/Transform",
    "geometry_msgs/Vector3", "geometry_msgs/Quaternion",
  ]),
  "std_msgs/msg/String": "string data",
};

const out = process.argv[2];
if (!out) {
  console.error("usage: ros2_scan_mcap_writer.mjs OUT.mcap");
  process.exit(2);
}

const chunks = [];
let position = 0n;
const writable = {
  position: () => position,
  write: async (buffer) => {
    chunks.push(Buffer.from(buffer));
    position += BigInt(buffer.byteLength);
  },
};
const writer = new McapWriter({ writable });
await writer.start({ profile: "ros2", library: "ros2_scan_mcap_writer" });

const channels = {};
const serialisers = {};
async function channel(topic, type) {
  const schemaId = await writer.registerSchema({
    name: type,
    encoding: "ros2msg",
    data: new TextEncoder().encode(types[type]),
  });
  channels[topic] = await writer.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: new Map() });
  serialisers[topic] = new rosmsg2.MessageWriter(rosmsg.parse(types[type], { ros2: true }));
}
await channel("/tf_static", "tf2_msgs/msg/TFMessage");
await channel("/odom", "nav_msgs/msg/Odometry");
await channel("/scan", "sensor_msgs/msg/LaserScan");
await channel("/chatter", "std_msgs/msg/String");

const sequence = {};
async function write(topic, t, data) {
  const bytes = data instanceof Uint8Array ? data : serialisers[topic].writeMessage(data);
  sequence[topic] = (sequence[topic] ?? 0) + 1;
  const time = BigInt(Math.round(t * 1e9));
  await writer.addMessage({ channelId: channels[topic], sequence: sequence[topic], logTime: time, publishTime: time, data: bytes });
}
const stamp = (t) => ({ sec: Math.floor(t), nanosec: Math.round((t - Math.floor(t)) * 1e9) });
const header = (t, frame) => ({ stamp: stamp(t), frame_id: frame });
const yawQuaternion = (yaw) => ({ x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) });
const zeros = new Array(36).fill(0);

await write("/tf_static", 100, {
  transforms: [
    { header: header(100, "base_footprint"), child_frame_id: "base_link",
      transform: { translation: { x: 0.1, y: 0, z: 0.2 }, rotation: yawQuaternion(0) } },
    { header: header(100, "base_link"), child_frame_id: "laser",
      transform: { translation: { x: 0.2, y: 0.1, z: 0.1 }, rotation: yawQuaternion(0.5) } },
  ],
});

const events = [];
for (let k = 0; k <= 100; ++k) events.push({ t: 100 + 0.05 * k, topic: "/odom" });
for (let j = 0; j < 24; ++j) events.push({ t: 100.01 + 0.2 * j, topic: "/scan" });
events.sort((a, b) => a.t - b.t);
const odometry = (t) => ({
  header: header(t, "odom"),
  child_frame_id: "base_footprint",
  pose: { pose: { position: { x: 0.5 * (t - 100), y: 0, z: 0 }, orientation: yawQuaternion(0.2 * (t - 100)) }, covariance: zeros },
  twist: { twist: { linear: { x: 0.5, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0.2 } }, covariance: zeros },
});
const scan = (t) => ({
  header: header(t, "laser"),
  angle_min: -1, angle_max: 1, angle_increment: 0.5, time_increment: 0, scan_time: 0.2,
  range_min: 0.05, range_max: 4,
  ranges: new Float32Array([1, 2, Infinity, 0.01, 3.5]),
  intensities: new Float32Array([]),
});
for (const e of events) await write(e.topic, e.t, e.topic === "/odom" ? odometry(e.t) : scan(e.t));
await write("/scan", 104.7, scan(101.0));
await write("/scan", 104.8, scan(110.0));
await write("/scan", 104.9, new Uint8Array([0, 1]));
await write("/chatter", 105, { data: "hello" });

await writer.end();
writeFileSync(out, Buffer.concat(chunks));

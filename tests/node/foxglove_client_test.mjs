// Drives a running slam-bridge with Foxglove's own client (@foxglove/ws-protocol's FoxgloveClient):
// connects, lists the channels, subscribes to all, checks every message against the JSON schema of
// its type (@foxglove/schemas for foxglove.*, the advertised schema otherwise, with ajv), decodes the
// CDR map channel (nav_msgs/msg/OccupancyGrid) with @foxglove/rosmsg2-serialization from the
// advertised ros2msg definition, calls the path service, then publishes a goal and waits until the
// robot drove toward it. With GRID_FILE, the first decoded OccupancyGrid with mapped (free) cells is
// written there as JSON (stamp, size, cells) for the caller to compare with the mapper's grid.
// Usage: node foxglove_client_test.mjs ws://127.0.0.1:8765 [timeout_s] [GRID_FILE]
// Exit 0 when everything held, 1 with one line saying what did not.
import { writeFileSync } from "node:fs";
import { createRequire } from "node:module";
import rosmsg from "@foxglove/rosmsg";
import rosmsg2 from "@foxglove/rosmsg2-serialization";
import wsProtocol from "@foxglove/ws-protocol";
import Ajv from "ajv";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol; // CommonJS packages: their exports come as the default
const { MessageReader } = rosmsg2;

const require = createRequire(import.meta.url);
const foxgloveSchemas = require("@foxglove/schemas/jsonschema");

const url = process.argv[2] ?? "ws://127.0.0.1:8765";
const timeoutS = Number(process.argv[3] ?? 90);
const gridFile = process.argv[4];
// Channels that must each carry at least one valid message (map updates, paths and alerts come only
// with change).
const required = ["/map", "/ros/map", "/robots", "/tf", "/points", "/health"];

const ajv = new Ajv({ strict: false, allErrors: true });
const decoder = new TextDecoder();
const channels = new Map(); // channel id -> channel
const bySubscription = new Map(); // subscription id -> { channel, validate }
const counts = new Map(); // topic -> valid messages
const robots = new Map(); // robot id -> {x, y} (from /tf)
let pathService;
let pathAnswer;
let goal; // { robot, target, startDistance }

function fail(message) {
  console.error(`foxglove_client_test: FAIL: ${message}`);
  process.exit(1);
}

// A CDR channel's decoder: the official ROS 2 reader over the advertised ros2msg definition.
function cdrDecoderFor(channel) {
  if (channel.schemaEncoding !== "ros2msg") fail(`${channel.topic} schema is ${channel.schemaEncoding}`);
  if (channel.schemaName !== "nav_msgs/msg/OccupancyGrid") fail(`${channel.topic}: unexpected ${channel.schemaName}`);
  return new MessageReader(rosmsg.parse(channel.schema, { ros2: true }));
}

// Checks a decoded OccupancyGrid; writes the first with a free cell to GRID_FILE.
let gridWritten = false;
function checkOccupancyGrid(topic, grid) {
  const { width, height } = grid.info;
  if (grid.header.frame_id !== "map") fail(`${topic}: frame ${grid.header.frame_id}, expected map`);
  if (grid.data.length !== width * height) fail(`${topic}: ${grid.data.length} cells for ${width} x ${height}`);
  for (const cell of grid.data)
    if (![-1, 0, 50, 100].includes(cell)) fail(`${topic}: cell value ${cell}`);
  if (gridFile && !gridWritten && grid.data.includes(0)) {
    const stampNs = BigInt(grid.header.stamp.sec) * 1000000000n + BigInt(grid.header.stamp.nanosec);
    const o = grid.info.origin.position;
    writeFileSync(gridFile, JSON.stringify({ stamp_ns: stampNs.toString(), width, height,
      resolution: grid.info.resolution, origin: [o.x, o.y], data: Array.from(grid.data) }));
    gridWritten = true;
  }
}

function validatorFor(channel) {
  if (channel.encoding === "cdr") return cdrDecoderFor(channel);
  if (channel.encoding !== "json") fail(`${channel.topic} is ${channel.encoding}, expected json`);
  if (channel.schemaEncoding !== "jsonschema") fail(`${channel.topic} schema is ${channel.schemaEncoding}`);
  if (channel.schemaName.startsWith("foxglove.")) {
    const schema = foxgloveSchemas[channel.schemaName.slice("foxglove.".length)];
    if (!schema) fail(`${channel.topic}: @foxglove/schemas has no ${channel.schemaName}`);
    return ajv.compile(schema);
  }
  return ajv.compile(JSON.parse(channel.schema));
}

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => fail(`connection error: ${e?.message ?? e}`));
client.on("close", () => {
  if (!done) fail("the server closed the connection");
});
client.on("serverInfo", (info) => {
  for (const capability of ["clientPublish", "services"])
    if (!info.capabilities.includes(capability)) fail(`serverInfo lacks capability ${capability}`);
  console.log(`serverInfo: ${info.name}, capabilities ${info.capabilities.join(", ")}`);
});
client.on("status", (s) => console.log(`status ${s.level}: ${s.message}`));
client.on("advertise", (list) => {
  for (const channel of list) {
    channels.set(channel.id, channel);
    const subscription = client.subscribe(channel.id);
    bySubscription.set(subscription, { channel, validate: validatorFor(channel) });
    console.log(`channel ${channel.id}: ${channel.topic} (${channel.schemaName})`);
  }
});
client.on("advertiseServices", (services) => {
  pathService = services.find((s) => s.name === "/plan_path");
  if (!pathService) fail("no /plan_path service advertised");
});
client.on("message", ({ subscriptionId, data }) => {
  const sub = bySubscription.get(subscriptionId);
  if (!sub) fail(`message for unknown subscription ${subscriptionId}`);
  if (sub.channel.encoding === "cdr") {
    let grid;
    try {
      grid = sub.validate.readMessage(data);
    } catch (e) {
      fail(`${sub.channel.topic}: not a CDR ${sub.channel.schemaName} (${e.message})`);
    }
    checkOccupancyGrid(sub.channel.topic, grid);
    counts.set(sub.channel.topic, (counts.get(sub.channel.topic) ?? 0) + 1);
    return;
  }
  let message;
  try {
    message = JSON.parse(decoder.decode(data));
  } catch (e) {
    fail(`${sub.channel.topic}: not JSON (${e.message})`);
  }
  if (!sub.validate(message))
    fail(`${sub.channel.topic}: does not match ${sub.channel.schemaName}: ${ajv.errorsText(sub.validate.errors)}`);
  counts.set(sub.channel.topic, (counts.get(sub.channel.topic) ?? 0) + 1);
  if (sub.channel.topic === "/tf")
    for (const t of message.transforms) robots.set(t.child_frame_id, { x: t.translation.x, y: t.translation.y });
});
client.on("serviceCallResponse", (response) => {
  const answer = JSON.parse(decoder.decode(response.data));
  const validate = ajv.compile(JSON.parse(pathService.response.schema));
  if (!validate(answer)) fail(`path answer does not match its schema: ${ajv.errorsText(validate.errors)}`);
  pathAnswer = answer;
  console.log(`path service: ${answer.status}, ${answer.path.length} points`);
});
client.on("serviceCallFailure", (f) => fail(`path service call failed: ${f.message}`));

const distance = (a, b) => Math.hypot(a.x - b.x, a.y - b.y);
let done = false;
const started = Date.now();
const timer = setInterval(() => {
  if ((Date.now() - started) / 1000 > timeoutS) {
    const missing = required.filter((t) => !counts.get(t));
    fail(
      `timed out: missing ${missing.join(", ") || "nothing"}; mapped grid ${gridWritten ? "yes" : "no"}; path answer ${pathAnswer ? "yes" : "no"}; goal ` +
        (goal ? `${goal.robot} now ${distance(robots.get(goal.robot), goal.target).toFixed(2)} m from target ` +
          `(was ${goal.startDistance.toFixed(2)})` : "not sent"),
    );
  }
  if (!goal && robots.size > 0 && pathService) {
    const [robot, at] = robots.entries().next().value;
    // Toward the middle of the 10 x 10 m empty world, or to a corner region when already there.
    const centre = { x: 5, y: 5 };
    const target = distance(at, centre) > 2 ? centre : { x: 2.5, y: 2.5 };
    const channel = client.advertise({ topic: "/goal", encoding: "json", schemaName: "slam.Goal" });
    const body = JSON.stringify({ robot_id: robot, x: target.x, y: target.y, mode: "direct" });
    client.sendMessage(channel, new TextEncoder().encode(body));
    client.sendServiceCallRequest({
      serviceId: pathService.id,
      callId: 1,
      encoding: "json",
      data: new TextEncoder().encode(JSON.stringify({ start: at, goal: target })),
    });
    goal = { robot, target, startDistance: distance(at, target) };
    console.log(`goal: ${robot} from (${at.x.toFixed(2)}, ${at.y.toFixed(2)}) to (${target.x}, ${target.y})`);
  }
  const moved = goal && distance(robots.get(goal.robot), goal.target) < goal.startDistance - 0.5;
  if (moved && pathAnswer && required.every((t) => counts.get(t) > 0) && (gridWritten || !gridFile)) {
    done = true;
    clearInterval(timer);
    console.log(`ok: ${[...counts].map(([t, n]) => `${t} ${n}`).join(", ")}`);
    client.close();
    process.exit(0);
  }
}, 100);

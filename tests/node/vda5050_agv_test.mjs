// A VDA 5050 2.0 robot no one here wrote: vda-5050-lib's AgvController with its VirtualAgvAdapter
// (pinned in package-lock.json), connected to the test's broker, driven by the gateway as its fleet
// control. It runs until killed (the test kills it, also with SIGKILL to break its connection) and logs
// one line per order update it takes, per node it passes and per pause and its end, for the test to read.
// OPERATING_MODE (optional, e.g. MANUAL) is switched to once started: a robot that rejects orders.
//   node vda5050_agv_test.mjs BROKER_URL MANUFACTURER SERIAL_NUMBER X Y MAP_ID [OPERATING_MODE]
import { AgvController, VirtualAgvAdapter } from "vda-5050-lib";

const [brokerUrl, manufacturer, serialNumber, x, y, mapId, operatingMode] = process.argv.slice(2);
if (!mapId) {
  console.error("usage: vda5050_agv_test.mjs BROKER_URL MANUFACTURER SERIAL_NUMBER X Y MAP_ID [OPERATING_MODE]");
  process.exit(2);
}

class LoggedAgvController extends AgvController {
  onStateChanged(changes) {
    if (changes.orderUpdateId !== undefined) {
      console.log(`order ${this.currentOrder?.orderId} update ${changes.orderUpdateId}`);
    }
    if (changes.lastNodeId !== undefined) {
      console.log(`node ${changes.lastNodeId} at ${this.currentOrder?.orderId}`);
    }
    // The state carries paused from the start; only its changes are logged.
    if (changes.paused !== undefined && changes.paused !== (this.paused ?? false)) {
      this.paused = changes.paused;
      console.log(this.paused ? "paused" : "unpaused");
    }
    for (const e of changes.errors ?? []) console.log(`error ${e.errorType}: ${e.errorDescription}`);
  }
}

const controller = new LoggedAgvController(
  { manufacturer, serialNumber },
  { interfaceName: "uagv", transport: { brokerUrl }, vdaVersion: "2.0.0" },
  // State at least once a second, the position ten times a second (the rates).
  { agvAdapterType: VirtualAgvAdapter, publishStateInterval: 1000, publishVisualizationInterval: 100 },
  {
    initialPosition: { mapId, x: Number(x), y: Number(y), theta: 0, lastNodeId: "start" },
    vehicleSpeed: 0.5,
    tickRate: 20,
  },
);

await controller.start();
if (operatingMode) controller.updateOperatingMode(operatingMode);
console.log(`started ${manufacturer}/${serialNumber} at (${x}, ${y}) on map ${mapId}`);
for (const signal of ["SIGTERM", "SIGINT"]) {
  process.on(signal, async () => {
    await controller.stop();
    process.exit(0);
  });
}

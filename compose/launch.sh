#!/usr/bin/env bash
# Local process-group launcher: starts mosquitto (unless --broker), every service that is built,
# simulated robots and the viewer (under Xvfb with PNG snapshots when there is no display).
# Logs: one file per service in $LOG_DIR. Ctrl-C / SIGTERM stops everything it started.
set -uo pipefail

BIN=${BIN:-build/bin}
DOMAIN=0
BROKER=""
PORT=1883
WORLD=office
ROBOTS=3
MODE=explore
HEADLESS=0
SIM=1
DATA=run/data
LOG_DIR=run/logs
SNAP_DIR=run/snapshots

usage() {
  cat <<USAGE
usage: scripts/run.sh [options]
  --headless         no window: the viewer renders under Xvfb and writes PNG snapshots
  --world NAME|FILE  simulated world (built-in: office, maze, track, empty; or a file)   [$WORLD]
  --robots N         simulated robots                                                   [$ROBOTS]
  --mode explore|idle  what the robots do at start                                      [$MODE]
  --no-sim           real robots only
  --domain N         DDS domain id                                                      [$DOMAIN]
  --broker URL       use this MQTT broker instead of starting mosquitto
  --port N           port of the local mosquitto                                        [$PORT]
  --data DIR         map store directory                                                [$DATA]
USAGE
}

while (($#)); do
  case "$1" in
    --headless) HEADLESS=1 ;;
    --world) WORLD=$2; shift ;;
    --robots) ROBOTS=$2; shift ;;
    --mode) MODE=$2; shift ;;
    --no-sim) SIM=0 ;;
    --domain) DOMAIN=$2; shift ;;
    --broker) BROKER=$2; shift ;;
    --port) PORT=$2; shift ;;
    --data) DATA=$2; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
case "$MODE" in explore|idle) ;; *) echo "run: --mode must be explore or idle" >&2; exit 2 ;; esac

mkdir -p "$LOG_DIR" "$DATA" "$SNAP_DIR"
declare -A PIDS=()

start() {  # start NAME CMD...: background process in its own group, output to $LOG_DIR/NAME.log
  local name=$1; shift
  if [ ! -x "$1" ] && ! command -v "$1" >/dev/null; then
    echo "run: $name not started ($1 is not built)"
    return
  fi
  setsid "$@" >"$LOG_DIR/$name.log" 2>&1 &
  PIDS[$name]=$!
  echo "run: started $name (pid $!, log $LOG_DIR/$name.log)"
}

stop_all() {
  trap - INT TERM
  echo "run: stopping ${!PIDS[*]}"
  for pid in "${PIDS[@]}"; do kill -TERM -- "-$pid" 2>/dev/null; done
  for _ in $(seq 50); do
    local alive=0
    for pid in "${PIDS[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${PIDS[@]}"; do kill -KILL -- "-$pid" 2>/dev/null; done
  exit 0
}
trap stop_all INT TERM

if [ -z "$BROKER" ]; then
  conf="$LOG_DIR/mosquitto.conf"
  printf 'listener %s 127.0.0.1\nallow_anonymous true\npersistence false\nmax_queued_messages 100000\n' "$PORT" >"$conf"
  start mosquitto mosquitto -c "$conf"
  BROKER="tcp://127.0.0.1:$PORT"
  sleep 0.5
fi

common=(--domain "$DOMAIN")
start gateway "$BIN/slam-gateway" "${common[@]}" --broker "$BROKER"
start mapper "$BIN/slam-mapper" "${common[@]}" --store "$DATA/map.db"
start planner "$BIN/slam-planner" "${common[@]}"
if ((SIM)); then
  start simulator "$BIN/slam-simulator" "${common[@]}" --broker "$BROKER" --world "$WORLD" --robots "$ROBOTS"
fi
if ((HEADLESS)) || [ -z "${DISPLAY:-}" ]; then
  echo "run: no display: the viewer writes a PNG snapshot every 10 s to $SNAP_DIR/"
  start viewer xvfb-run -a -s "-screen 0 1280x800x24" "$BIN/slam-viewer" "${common[@]}" --snapshot-dir "$SNAP_DIR" --snapshot-period 10
else
  start viewer "$BIN/slam-viewer" "${common[@]}"
fi
if ((SIM)) && [ "$MODE" = explore ] && [ -x "$BIN/slamctl" ]; then
  sleep 2
  "$BIN/slamctl" --domain "$DOMAIN" goal all explore >>"$LOG_DIR/slamctl.log" 2>&1 &
fi

echo "run: running; Ctrl-C stops everything"
while true; do
  for name in "${!PIDS[@]}"; do
    if ! kill -0 "${PIDS[$name]}" 2>/dev/null; then
      echo "run: $name exited; last lines of $LOG_DIR/$name.log:" >&2
      tail -n 20 "$LOG_DIR/$name.log" >&2
      unset "PIDS[$name]"
    fi
  done
  sleep 1
done

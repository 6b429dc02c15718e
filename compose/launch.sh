#!/usr/bin/env bash
# Local process-group launcher: starts mosquitto (unless --broker), every service that is built,
# simulated robots and the viewer (on its own Xvfb server, writing PNG snapshots, when there is no
# display). Logs: one file per service in $LOG_DIR. Ctrl-C / SIGTERM stops everything it started:
# the services and the viewer first, then the X server and the broker they were connected to.
# --secure: MQTT over TLS with passwords and the ACL, DDS Security on every Fast DDS program
# (files made by compose/make-security.sh into --data on first use; docs/security.md).
set -uo pipefail

BIN=${BIN:-build/bin}
DOMAIN=0
BROKER=""
PORT=1883
WORLD=office
ROBOTS=3
VDA_ROBOTS=0
GATEWAYS=1
PLANNERS=1
MODE=explore
HEADLESS=0
SIM=1
FRESH=0
SECURE=0
DATA=run/data
LOG_DIR=run/logs
SNAP_DIR=run/snapshots
SNAP_PERIOD=10
BRIDGE=1
BRIDGE_BIND=127.0.0.1:8765
BUILT_IN_WORLDS="office maze track rooms empty"

usage() {
  cat <<USAGE
usage: scripts/run.sh [options]      (or BIN=build/bin compose/launch.sh [options])
  --headless           no window: the viewer renders under Xvfb and writes PNG snapshots
                       (also the default when \$DISPLAY is not set)
  --world NAME|FILE    simulated world (built-in: ${BUILT_IN_WORLDS// /, }; or a world file) [$WORLD]
  --robots N           simulated robots (0..5000)                                   [$ROBOTS]
  --vda-robots N       of them, the first N speak VDA 5050 (docs/protocol.md); one
                       gateway, not with --secure                                   [$VDA_ROBOTS]
  --gateways N         gateways sharing the robots (1..8)                           [$GATEWAYS]
  --planners N         planners sharing the goals and path requests (1..8), each
                       with its own goal file in --data                             [$PLANNERS]
  --mode explore|idle  explore: send every robot exploring at start; idle: wait for goals
                       (goals kept in --data from an earlier run resume either way)  [$MODE]
  --no-sim             real robots only
  --no-bridge          no Foxglove bridge (docs/ecosystem.md)
  --bridge-bind A:P    where the Foxglove bridge listens (0.0.0.0:8765: every interface) [$BRIDGE_BIND]
  --fresh              start afresh: deletes the map store and the planner's goals in --data
  --secure             MQTT over TLS (passwords, ACL; mutual TLS on --port + 1) and DDS
                       Security; certificates and permissions in --data/security (made on
                       first use); the simulator's DDS side moves to domain --domain + 1,
                       unsecured (docs/security.md)
  --domain N           DDS domain id (0..232)                                       [$DOMAIN]
  --broker URL         use this MQTT broker instead of starting mosquitto
  --port N             port of the local mosquitto                                  [$PORT]
  --data DIR           map store and planner goal file directory                    [$DATA]
  --logs DIR           one log file per service                                     [$LOG_DIR]
  --snapshots DIR      headless viewer: snapshot-NNNN.png and latest.png go here    [$SNAP_DIR]
  --snapshot-period S  headless viewer: seconds between snapshots                   [$SNAP_PERIOD]
Programs come from \$BIN [$BIN]. Ctrl-C stops everything this script started.
USAGE
}

fail() {  # fail MESSAGE: a bad option or setup problem, one line, exit status 2
  echo "run: $1" >&2
  exit 2
}

need_value() {  # need_value OPTION ARGC: the option must be followed by a value
  (($2 >= 2)) || fail "$1 needs a value (see --help)"
}

is_uint() { [[ $1 =~ ^[0-9]+$ ]] && ((10#$1 <= 1000000)); }

while (($#)); do
  case "$1" in
    --headless) HEADLESS=1 ;;
    --no-sim) SIM=0 ;;
    --no-bridge) BRIDGE=0 ;;
    --fresh) FRESH=1 ;;
    --secure) SECURE=1 ;;
    --world | --robots | --vda-robots | --gateways | --planners | --mode | --domain | --broker | --port | --data | --logs | --snapshots | --snapshot-period | --bridge-bind)
      need_value "$1" $#
      case "$1" in
        --world) WORLD=$2 ;;
        --robots) ROBOTS=$2 ;;
        --vda-robots) VDA_ROBOTS=$2 ;;
        --gateways) GATEWAYS=$2 ;;
        --planners) PLANNERS=$2 ;;
        --mode) MODE=$2 ;;
        --domain) DOMAIN=$2 ;;
        --broker) BROKER=$2 ;;
        --port) PORT=$2 ;;
        --data) DATA=$2 ;;
        --logs) LOG_DIR=$2 ;;
        --snapshots) SNAP_DIR=$2 ;;
        --snapshot-period) SNAP_PERIOD=$2 ;;
        --bridge-bind) BRIDGE_BIND=$2 ;;
      esac
      shift ;;
    -h | --help) usage; exit 0 ;;
    *) fail "unknown option $1 (see --help)" ;;
  esac
  shift
done

case "$MODE" in explore | idle) ;; *) fail "--mode must be explore or idle, got '$MODE'" ;; esac
is_uint "$ROBOTS" && ((10#$ROBOTS <= 5000)) || fail "--robots must be 0..5000, got '$ROBOTS'"
is_uint "$VDA_ROBOTS" && ((10#$VDA_ROBOTS <= 10#$ROBOTS)) || fail "--vda-robots must be 0..--robots, got '$VDA_ROBOTS'"
is_uint "$GATEWAYS" && ((10#$GATEWAYS >= 1 && 10#$GATEWAYS <= 8)) || fail "--gateways must be 1..8, got '$GATEWAYS'"
is_uint "$PLANNERS" && ((10#$PLANNERS >= 1 && 10#$PLANNERS <= 8)) || fail "--planners must be 1..8, got '$PLANNERS'"
is_uint "$DOMAIN" && ((10#$DOMAIN <= 232)) || fail "--domain must be 0..232, got '$DOMAIN'"
is_uint "$PORT" && ((10#$PORT >= 1 && 10#$PORT <= 65535)) || fail "--port must be 1..65535, got '$PORT'"
# VDA robots' orders need the gateway that heard them, and the secure broker's ACL knows the v1/v2 trees only.
((10#$VDA_ROBOTS == 0 || (10#$GATEWAYS == 1 && !SECURE))) || fail "--vda-robots needs one gateway and no --secure"
[[ $SNAP_PERIOD =~ ^[0-9]+([.][0-9]+)?$ ]] || fail "--snapshot-period must be a number of seconds, got '$SNAP_PERIOD'"
if ((SIM)) && [[ " $BUILT_IN_WORLDS " != *" $WORLD "* ]] && [ ! -r "$WORLD" ]; then
  fail "--world '$WORLD' is neither a built-in world (${BUILT_IN_WORLDS// /, }) nor a readable file"
fi
HEADLESS_VIEWER=0
if ((HEADLESS)) || [ -z "${DISPLAY:-}" ]; then
  HEADLESS_VIEWER=1
  command -v Xvfb >/dev/null || fail "no display and no Xvfb: install xvfb (apt-get install xvfb) or set DISPLAY"
fi

mkdir -p "$LOG_DIR" "$DATA" || fail "cannot create $LOG_DIR or $DATA"
if ((HEADLESS_VIEWER)); then
  mkdir -p "$SNAP_DIR" || fail "cannot create $SNAP_DIR"
  snap_abs=$(cd "$SNAP_DIR" && pwd)
fi
if ((FRESH)); then
  rm -f "$DATA"/map.db "$DATA"/map.db-* "$DATA/world" "$DATA"/goals.json "$DATA"/goals-*.json
  echo "run: --fresh: removed the map store and the planners' goals in $DATA"
elif ((SIM)) && [ -f "$DATA/map.db" ] && [ -f "$DATA/world" ] && [ "$(cat "$DATA/world")" != "$WORLD" ]; then
  echo "run: note: the map store in $DATA was built in world '$(cat "$DATA/world")', now '$WORLD': the map mixes both (add --fresh to start empty)" >&2
fi
((SIM)) && echo "$WORLD" >"$DATA/world"

declare -A PIDS=()
HELPER_PIDS=()
INFRA="mosquitto xvfb"  # stopped last: the others are their clients

start() {  # start NAME CMD...: background process in its own group, output to $LOG_DIR/NAME.log
  local name=$1; shift
  if [ ! -x "$1" ] && ! command -v "$1" >/dev/null; then
    echo "run: $name not started ($1 is not built)"
    return
  fi
  # Secure mode: a DDS program joins as the identity its name says ("gateway-2" -> gateway).
  local identity=()
  ((SECURE)) && identity=(env "SLAM_DDS_IDENTITY=${name%%-[0-9]*}")
  setsid "${identity[@]}" "$@" >"$LOG_DIR/$name.log" 2>&1 &
  PIDS[$name]=$!
  echo "run: started $name (pid $!, log $LOG_DIR/$name.log)"
}

stop_groups() {  # stop_groups NAME...: TERM each process group, KILL what is left after 5 s
  local pids=()
  for name in "$@"; do [ -n "${PIDS[$name]:-}" ] && pids+=("${PIDS[$name]}"); done
  ((${#pids[@]})) || return 0
  for pid in "${pids[@]}"; do kill -TERM -- "-$pid" 2>/dev/null; done
  for _ in $(seq 50); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -KILL -- "-$pid" 2>/dev/null; done
}

stop_all() {  # stop_all STATUS
  trap - INT TERM HUP
  local status=${1:-0} clients=() infra=()
  for pid in "${HELPER_PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null; done
  for name in "${!PIDS[@]}"; do
    if [[ " $INFRA " == *" $name "* ]]; then infra+=("$name"); else clients+=("$name"); fi
  done
  if ((${#PIDS[@]})); then
    local all=("${clients[@]}" "${infra[@]}")
    echo "run: stopping ${all[*]}"
    stop_groups "${clients[@]}"
    stop_groups "${infra[@]}"
  fi
  wait 2>/dev/null
  echo "run: stopped; logs in $LOG_DIR/${SNAP_NOTE:-}"
  exit "$status"
}
trap 'stop_all 0' INT TERM
trap 'stop_all 1' HUP  # the terminal went away: do not leave the services running
trap '' PIPE           # stdout piped into a reader that quit (| head): keep managing the processes

gateway_mqtt=()
sim_mqtt=()
SIM_DOMAIN=$DOMAIN
if ((SECURE)); then
  SECURITY=$DATA/security
  bash compose/make-security.sh "$SECURITY" >"$LOG_DIR/make-security.log" 2>&1 ||
    { cat "$LOG_DIR/make-security.log" >&2; fail "compose/make-security.sh failed"; }
  SECURITY=$(cd "$SECURITY" && pwd)
  export SLAM_DDS_SECURITY_DIR=$SECURITY
  echo "run: secure mode: certificates and permissions in $SECURITY"
  # MQTT passwords made once; every simulated robot logs in as its id (sim-N) with one of them.
  (umask 077
   [ -s "$SECURITY/mqtt-gateway.password" ] || openssl rand -hex 16 >"$SECURITY/mqtt-gateway.password"
   [ -s "$SECURITY/mqtt-sim.password" ] || openssl rand -hex 16 >"$SECURITY/mqtt-sim.password"
   printf 'username: gateway\npassword: %s\n' "$(cat "$SECURITY/mqtt-gateway.password")" >"$SECURITY/gateway.yaml"
   printf 'mqtt-password: %s\n' "$(cat "$SECURITY/mqtt-sim.password")" >"$SECURITY/simulator.yaml")
  gateway_mqtt=(--tls-ca-file "$SECURITY/ca.crt" --config "$SECURITY/gateway.yaml")
  sim_mqtt=(--tls-ca-file "$SECURITY/ca.crt" --config "$SECURITY/simulator.yaml")
  # Cyclone 0.10 and Fast DDS 2.9 cannot complete a secure handshake: docs/security.md.
  SIM_DOMAIN=$(((10#$DOMAIN + 1) % 233))
fi

if [ -z "$BROKER" ]; then
  conf="$LOG_DIR/mosquitto.conf"
  if ((SECURE)); then
    # Accounts: the gateway, sim-1 .. sim-N with room for robots added while running, and the real
    # robots listed as ID:PASSWORD lines in $SECURITY/mqtt-robots (kept by the operator).
    passwords="$SECURITY/mqtt-passwords"
    (umask 077
     { echo "gateway:$(cat "$SECURITY/mqtt-gateway.password")"
       for i in $(seq $((10#$ROBOTS + 64))); do echo "sim-$i:$(cat "$SECURITY/mqtt-sim.password")"; done
       [ ! -r "$SECURITY/mqtt-robots" ] || grep -v -e '^#' -e '^[[:space:]]*$' "$SECURITY/mqtt-robots" || true
     } >"$passwords") && mosquitto_passwd -U "$passwords" || fail "cannot write $passwords (mosquitto_passwd)"
    # compose/mosquitto/mosquitto-secure.conf on the loopback port. `user`: mosquitto started as root
    # would read the keys as user mosquitto otherwise.
    # Robots with a certificate of the CA connect to the port after --port (mutual TLS).
    sed -e "s|^listener 8883|listener $PORT 127.0.0.1|" -e "s|^listener 8884|listener $((10#$PORT + 1)) 127.0.0.1|" \
      -e "s|SECURITY/|$SECURITY/|" -e "s|^acl_file .*|acl_file $PWD/compose/mosquitto/acl|" \
      compose/mosquitto/mosquitto-secure.conf >"$conf"
    echo "user $(id -un)" >>"$conf"
    BROKER="ssl://127.0.0.1:$PORT"
  else
    printf 'listener %s 127.0.0.1\nallow_anonymous true\npersistence false\nmax_queued_messages 100000\n' "$PORT" >"$conf"
    BROKER="tcp://127.0.0.1:$PORT"
  fi
  start mosquitto mosquitto -c "$conf"
  sleep 0.5
  if [ -z "${PIDS[mosquitto]:-}" ] || ! kill -0 "${PIDS[mosquitto]}" 2>/dev/null; then
    echo "run: mosquitto did not start (port $PORT in use? try --port); its log:" >&2
    tail -n 5 "$LOG_DIR/mosquitto.log" >&2
    stop_all 1
  fi
fi

common=(--domain "$DOMAIN")
instance_name() {  # instance_name SERVICE I N: "gateway" alone, "gateway-2" among several
  if (($3 == 1)); then echo "$1"; else echo "$1-$2"; fi
}
for i in $(seq "$GATEWAYS"); do
  start "$(instance_name gateway "$i" "$GATEWAYS")" "$BIN/slam-gateway" "${common[@]}" --broker "$BROKER" "${gateway_mqtt[@]}"
done
start mapper "$BIN/slam-mapper" "${common[@]}" --store "$DATA/map.db"
# Each planner keeps its own goal file (every one follows every goal: docs/deployment.md).
for i in $(seq "$PLANNERS"); do
  name=$(instance_name planner "$i" "$PLANNERS")
  goals="$DATA/goals.json"
  ((PLANNERS == 1)) || goals="$DATA/goals-$i.json"
  start "$name" "$BIN/slam-planner" "${common[@]}" --goal-store "$goals"
done
if ((BRIDGE)); then
  start bridge "$BIN/slam-bridge" "${common[@]}" --bind "$BRIDGE_BIND"
  [ -n "${PIDS[bridge]:-}" ] && echo "run: Foxglove / Lichtblick: connect to ws://$BRIDGE_BIND (docs/ecosystem.md)"
fi
if ((SIM)); then
  start simulator "$BIN/slam-simulator" --domain "$SIM_DOMAIN" --broker "$BROKER" "${sim_mqtt[@]}" --world "$WORLD" --robots "$ROBOTS" --vda-robots "$VDA_ROBOTS"
fi
if [ ! -x "$BIN/slam-viewer" ]; then
  echo "run: viewer not started ($BIN/slam-viewer is not built)"
elif ((HEADLESS_VIEWER)); then
  # Our own X server (not xvfb-run) so the viewer can be stopped before it; -displayfd lets Xvfb
  # pick a free display and tell us which.
  display_file="$LOG_DIR/xvfb.display"
  : >"$display_file"
  exec 3>"$display_file"
  start xvfb Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp
  exec 3>&-
  for _ in $(seq 100); do [ -s "$display_file" ] && break; sleep 0.1; done
  if [ ! -s "$display_file" ]; then
    echo "run: Xvfb did not start; its log:" >&2
    tail -n 5 "$LOG_DIR/xvfb.log" >&2
    stop_all 1
  fi
  # Nobody watches the frames under Xvfb: 10 frames per second leave the CPU to the services.
  start viewer env DISPLAY=":$(head -n 1 "$display_file")" "$BIN/slam-viewer" "${common[@]}" --fps 10 \
    --snapshot-dir "$SNAP_DIR" --snapshot-period "$SNAP_PERIOD"
  SNAP_NOTE="; viewer snapshots in $snap_abs/"
  echo "run: no display: the viewer writes a PNG every $SNAP_PERIOD s to $snap_abs/snapshot-NNNN.png;"
  echo "run:   the newest is always $snap_abs/latest.png"
else
  start viewer "$BIN/slam-viewer" "${common[@]}"
fi
if ((SIM)) && [ "$MODE" = explore ]; then
  if [ -x "$BIN/slamctl" ]; then
    # "all" also reaches robots the planner has not seen yet; slamctl gives up after --timeout.
    as_slamctl=()
    ((SECURE)) && as_slamctl=(env SLAM_DDS_IDENTITY=slamctl)
    ( sleep 2 && exec "${as_slamctl[@]}" "$BIN/slamctl" --domain "$DOMAIN" --timeout 60 goal all explore ) >>"$LOG_DIR/slamctl.log" 2>&1 &
    HELPER_PIDS+=($!)
    echo "run: robots will explore (slamctl goal all explore, log $LOG_DIR/slamctl.log)"
  else
    echo "run: $BIN/slamctl is not built: robots stay idle (--mode explore needs it)" >&2
  fi
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

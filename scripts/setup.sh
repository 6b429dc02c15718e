#!/usr/bin/env bash
# Installs every Debian package the project needs (idempotent: apt runs only when something is missing),
# then configures and builds in Release. Usage: scripts/setup.sh [BUILD_DIR]
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config clang clang-format
  libfastrtps-dev fastddsgen fastdds-tools
  cyclonedds-dev cyclonedds-tools
  libompl-dev libeigen3-dev libceres-dev libnanoflann-dev
  libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  libpaho-mqtt-dev mosquitto mosquitto-clients
  libglfw3-dev libimgui-dev libgl-dev libx11-dev libgl1-mesa-dri xvfb xauth
  libgtest-dev libgmock-dev libbenchmark-dev
  libsqlite3-dev libcli11-dev libspdlog-dev nlohmann-json3-dev libyaml-cpp-dev libstb-dev
  libwebsocketpp-dev libasio-dev  # the bridge's WebSocket server (header-only, standalone asio)
  libzstd-dev liblz4-dev  # compressed chunks in MCAP recordings (ros2 bag, the mcap CLI)
  nodejs  # runs Foxglove's own client against the bridge in tests (tests/node)
  jq openssl
  docker-compose  # validates compose/docker-compose.yml in tests (no Docker engine needed)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm: Debian ships it apart from nodejs; a nodejs from elsewhere (NodeSource) brings its own, and
# Debian's npm package would conflict with it, so it is installed only when no npm command exists.
if ! command -v npm >/dev/null 2>&1; then
  echo "setup: installing npm"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends npm
fi

# The pinned npm packages of the Node tests (tests/node/package-lock.json), again only when the lock
# file changed since the last install. Without the registry the build goes on and the bridge test
# says what is missing.
NODE_DIR="$(dirname "$0")/../tests/node"
if [ ! -f "$NODE_DIR/node_modules/.package-lock.json" ] ||
  [ "$NODE_DIR/package-lock.json" -nt "$NODE_DIR/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in tests/node"
  (cd "$NODE_DIR" && npm ci --no-audit --no-fund --loglevel=error) ||
    echo "setup: warning: npm ci failed in tests/node; the bridge's Node test will fail until it succeeds" >&2
fi

# Configure once, then build incrementally (Ninja). SLAM_CMAKE_ARGS adds options, e.g. -DSLAM_SANITIZE=ON.
BUILD_DIR="${1:-build}"
cd "$(dirname "$0")/.."
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release ${SLAM_CMAKE_ARGS:-}
fi
cmake --build "$BUILD_DIR" -j "$(nproc)"

#!/usr/bin/env bash
# The run command: installs what is missing, builds, and starts the whole system on this machine
# (compose/launch.sh; --help lists its options). Ctrl-C stops everything it started.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh build
exec bash compose/launch.sh "$@"

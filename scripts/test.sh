#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs every registered test (unit,
# integration, fuzz smoke runs). Exit code non-zero on any failure. Extra arguments go to ctest,
# e.g. scripts/test.sh -L unit   or   scripts/test.sh -R gateway
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh build
# House style is part of the test: a file clang-format would change fails the run (fix: scripts/format.sh).
bash scripts/format.sh --check
# Each integration test owns a DDS domain and broker port, so tests run in parallel.
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" -LE bench "$@"

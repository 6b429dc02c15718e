#!/usr/bin/env bash
# Builds every program and test with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/) and
# runs the unit and integration tests under them. On an idle 2-core machine a full build takes about
# 45 minutes and the tests about 10, so it is not part of scripts/test.sh; run it before a release
# and after touching memory-heavy code.
# Extra arguments go to ctest, e.g. scripts/sanitize.sh -L unit   or   scripts/sanitize.sh -R Mapper
set -euo pipefail
cd "$(dirname "$0")/.."
SLAM_CMAKE_ARGS="-DSLAM_SANITIZE=ON ${SLAM_CMAKE_ARGS:-}" bash scripts/setup.sh build-asan
# new_delete_type_mismatch: libfastrtps 2.9 deletes its StatisticsWriterImpl through the wrong type
# (a library bug, reported for every test that deletes a writer). halt_on_error: the first finding
# fails the test. The LeakSanitizer suppressions cover the Mesa GL driver only.
export ASAN_OPTIONS="new_delete_type_mismatch=0:halt_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitize.supp:print_suppressions=0"
ctest --test-dir build-asan --output-on-failure --timeout 1200 -j "$(nproc)" -LE 'bench|fuzz' "$@"

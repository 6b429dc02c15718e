#!/usr/bin/env bash
# clang-format over every C++ source the project owns (.clang-format at the top).
# Usage: scripts/format.sh          rewrite files in place
#        scripts/format.sh --check  change nothing; non-zero and the offending lines when a file is off
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' ':!:tests/fuzz/corpus/*')
if [ "${1:-}" = "--check" ]; then
  clang-format --dry-run -Werror "${files[@]}"
  echo "format: ${#files[@]} files match .clang-format"
else
  clang-format -i "${files[@]}"
fi

#!/usr/bin/env bash
# The benchmark command: sets up and builds (scripts/setup.sh), runs every bench_* program with
# --benchmark_format=json, keeps the JSON in BUILD/bench/, and prints one table of figures against
# their targets (the mapping lives in scripts/bench_table.jq). See docs/performance.md.
# "mapping" is the evaluation against the simulator's ground truth (eval_mapping, a run matrix; JSON
# and images in BUILD/bench/mapping/, table by scripts/mapping_table.jq, docs/mapping-quality.md).
#   scripts/bench.sh                  full runs (about 10 minutes after the build; not yet timed whole)
#   scripts/bench.sh --quick          short runs of every program (about 2 minutes), same table
#   scripts/bench.sh --write-docs     also replace the generated tables in docs/performance.md and
#                                     (when mapping ran) docs/mapping-quality.md
#   scripts/bench.sh --only gateway,pipeline   run these programs only (the table uses the JSON
#                                              other programs left in BUILD/bench/ earlier)
#   scripts/bench.sh --only mapping   the mapping evaluation only (about 50 minutes; --quick: one
#                                     2-simulated-minute run). SLAM_EVAL_SPEED sets its speed factor.
#   scripts/bench.sh --only logs --logs DIR   real robots' logs: every CARMEN log under DIR (*.clf or
#                                     *.clf.gz, with its .relations beside it) through eval_log, all
#                                     beams, 16 beams at 8 m and as a v1 robot, scored with the
#                                     benchmark's relation metric (JSON and maps in BUILD/bench/logs/)
set -euo pipefail
cd "$(dirname "$0")/.."

ALL=(protocol mapper planner simulator gateway viewer pipeline slam mapping logs)
BUILD_DIR=build
QUICK=0
WRITE_DOCS=0
ONLY=""
LOGS_DIR=""
DOC=docs/performance.md
MAPPING_DOC=docs/mapping-quality.md

usage() { sed -n '2,17s/^# \{0,1\}//p' "$0"; echo "  --build-dir DIR  build and run in DIR [build]"; }
while (($#)); do
  case "$1" in
    --quick) QUICK=1 ;;
    --write-docs) WRITE_DOCS=1 ;;
    --only) ONLY=${2:?--only needs a comma-separated list}; shift ;;
    --build-dir) BUILD_DIR=${2:?--build-dir needs a directory}; shift ;;
    --logs) LOGS_DIR=${2:?--logs needs a directory}; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "bench: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
SELECTED=("${ALL[@]}")
if [ -n "$ONLY" ]; then
  IFS=, read -r -a SELECTED <<<"$ONLY"
  for name in "${SELECTED[@]}"; do
    [[ " ${ALL[*]} " == *" $name "* ]] || { echo "bench: --only: unknown program '$name' (known: ${ALL[*]})" >&2; exit 2; }
  done
fi

bash scripts/setup.sh "$BUILD_DIR"
command -v jq >/dev/null || { echo "bench: jq is missing (scripts/setup.sh installs it)" >&2; exit 1; }

OUT="$BUILD_DIR/bench"
mkdir -p "$OUT"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)

# Extra arguments and environment per program. Quick mode shortens the adaptive runs and the
# message counts; programs with fixed iteration counts (rebuild, viewer frames) keep them.
args_for() {
  local name=$1
  if ((QUICK)); then
    case "$name" in
      gateway|pipeline) ;;  # not adaptive: shortened through the environment below
      *) echo "--benchmark_min_time=0.05" ;;
    esac
  fi
}
env_for() {
  local name=$1
  if ((QUICK)); then
    case "$name" in
      gateway) echo "SLAM_BENCH_GATEWAY_MESSAGES=20000" ;;
      pipeline) echo "SLAM_BENCH_PIPELINE_SECONDS=10" ;;
    esac
  fi
}

# The mapping matrix: one eval_mapping run per line (its arguments). Every world with correction
# on and off at the simulator's default drift; in the office also v2 robots, drift 0 (the reference:
# position and heading drift off) and twice the default drift. Then three runs whose robots patrol
# the mapped building once exploration is done (--patrol: its own table).
mapping_runs() {
  if ((QUICK)); then
    echo "--world office --protocol v1 --duration 120"
    return
  fi
  local world slam
  local zero="--drift 0 --sim-arg=--heading-drift --sim-arg=0"
  local twice="--drift 0.04 --sim-arg=--heading-drift --sim-arg=0.02"
  for world in office maze track rooms; do
    for slam in on off; do
      echo "--world $world --protocol v1 --mapper-arg=--slam --mapper-arg=$slam"
    done
  done
  for slam in on off; do
    echo "--world office --protocol v2 --mapper-arg=--slam --mapper-arg=$slam"
    echo "--world office --protocol v1 $zero --mapper-arg=--slam --mapper-arg=$slam"
    echo "--world office --protocol v1 $twice --mapper-arg=--slam --mapper-arg=$slam"
  done
  echo "--world office --protocol v1 --patrol"
  echo "--world maze --protocol v1 --patrol"
  echo "--world office --protocol v1 $twice --patrol"
}

# Runs the mapping matrix into $OUT/mapping (earlier results of other runs stay); a failed run is
# reported and skipped (a world the simulator does not have yet, for one).
run_mapping() {
  local bin="$BUILD_DIR/bin/eval_mapping" dir="$OUT/mapping" line n=0
  [ -x "$bin" ] || { echo "bench: $bin is not built; skipped" >&2; failed+=("mapping (not built)"); return; }
  mkdir -p "$dir"
  while read -r line; do
    n=$((n + 1))
    local log="$dir/run_$n.log" start=$SECONDS
    read -r -a run_args <<<"$line"
    echo "bench: eval_mapping $line (log $log)"
    if ! "$bin" --out "$dir" --speed "${SLAM_EVAL_SPEED:-8}" "${run_args[@]}" >"$log" 2>&1; then
      echo "bench: eval_mapping $line failed; last lines of $log:" >&2
      tail -n 5 "$log" >&2
      failed+=("mapping ($line)")
      continue
    fi
    echo "bench: done in $((SECONDS - start)) s"
  done < <(mapping_runs)
}

# Every CARMEN log under $LOGS_DIR with its relation file, three ways each (eval_log: all beams, a
# sparse 16-beam robot seeing 8 m, a legacy v1 robot), two at a time, into $OUT/logs.
run_logs() {
  local bin="$BUILD_DIR/bin/eval_log" dir="$OUT/logs" log_file
  [ -n "$LOGS_DIR" ] || { echo "bench: logs: no --logs DIR given; skipped"; return; }
  [ -d "$LOGS_DIR" ] || { echo "bench: --logs $LOGS_DIR: no such directory" >&2; failed+=("logs"); return; }
  [ -x "$bin" ] || { echo "bench: $bin is not built; skipped" >&2; failed+=("logs (not built)"); return; }
  mkdir -p "$dir"
  local -a runs=()
  while IFS= read -r log_file; do
    local stem=${log_file%.gz}
    stem=${stem%.clf}
    [ -f "$stem.relations" ] || { echo "bench: $log_file has no $stem.relations; skipped" >&2; continue; }
    runs+=("$log_file" "$log_file --beams 16 --max-range 8" "$log_file --v1 --beams 16 --max-range 8")
  done < <(find "$LOGS_DIR" -name '*.clf' -o -name '*.clf.gz' | sort)
  ((${#runs[@]})) || { echo "bench: no CARMEN log with a relation file under $LOGS_DIR" >&2; failed+=("logs"); return; }
  printf '%s\n' "${runs[@]}" | xargs -P 2 -I{} sh -c "echo 'bench: eval_log {}'; $bin --out $dir {}" ||
    failed+=("logs")
}

failed=()
for name in "${SELECTED[@]}"; do
  if [ "$name" = mapping ]; then
    run_mapping
    continue
  fi
  if [ "$name" = logs ]; then
    run_logs
    continue
  fi
  bin="$BUILD_DIR/bin/bench_$name"
  json="$OUT/bench_$name.json"
  log="$OUT/bench_$name.log"
  rm -f "$json"
  if [ ! -x "$bin" ]; then
    echo "bench: $bin is not built; skipped" >&2
    failed+=("$name (not built)")
    continue
  fi
  cmd=("$bin" --benchmark_format=json "--benchmark_out=$json" --benchmark_out_format=json)
  read -r -a extra <<<"$(args_for "$name")"
  cmd+=("${extra[@]}")
  # The viewer renders through GLFW: without a display it runs under Xvfb (Mesa llvmpipe).
  # -noreset: each benchmark closes its window, and an Xvfb resetting after its last client
  # refuses the next benchmark's connection.
  if [ "$name" = viewer ] && [ -z "${DISPLAY:-}" ]; then
    cmd=(xvfb-run -a -s "-screen 0 1280x800x24 -noreset" "${cmd[@]}")
  fi
  read -r -a environment <<<"$(env_for "$name")"
  echo "bench: running bench_$name (log $log)"
  start=$SECONDS
  if ! env "${environment[@]}" "${cmd[@]}" >"$log" 2>&1; then
    echo "bench: bench_$name failed; last lines of $log:" >&2
    tail -n 15 "$log" >&2
    rm -f "$json"  # cut off mid-run: the table shows its figures as not run
    failed+=("$name")
    continue
  fi
  if ! jq -e . "$json" >/dev/null 2>&1; then
    failed+=("$name (no JSON)")
    continue
  fi
  errors=$(jq -r '.benchmarks[] | select(.error_occurred) | "\(.name): \(.error_message)"' "$json")
  if [ -n "$errors" ]; then
    echo "bench: bench_$name reported errors:" >&2
    echo "$errors" >&2
    failed+=("$name")
  fi
  echo "bench: bench_$name done in $((SECONDS - start)) s"
done

load_after=$(cut -d' ' -f1-3 /proc/loadavg)
mode=$( ((QUICK)) && echo "scripts/bench.sh --quick" || echo "scripts/bench.sh")

# Replaces the lines between <!-- MARKER:begin --> and <!-- MARKER:end --> in DOC with BLOCK.
write_block() {
  local doc=$1 marker=$2 block=$3
  grep -q "<!-- $marker:begin -->" "$doc" && grep -q "<!-- $marker:end -->" "$doc" ||
    { echo "bench: $doc has no <!-- $marker:begin/end --> markers" >&2; exit 1; }
  BLOCK="$block" BEGIN_MARK="<!-- $marker:begin -->" END_MARK="<!-- $marker:end -->" awk '
    index($0, ENVIRON["BEGIN_MARK"]) { print; print ENVIRON["BLOCK"]; skip = 1; next }
    index($0, ENVIRON["END_MARK"]) { skip = 0 }
    !skip { print }' "$doc" >"$doc.tmp"
  mv "$doc.tmp" "$doc"
  echo "bench: table written to $doc"
}

shopt -s nullglob
benchmarks_selected=0
for name in "${SELECTED[@]}"; do [ "$name" = mapping ] || [ "$name" = logs ] || benchmarks_selected=1; done
if ((benchmarks_selected)); then
  results=("$OUT"/bench_*.json)
  table=$(jq -n -r -f scripts/bench_table.jq "${results[@]}")
  header="Generated by \`$mode\` on $(date +%Y-%m-%d) ($(nproc) cores; load average $load_before before, $load_after after)."
  echo
  echo "$header"
  echo
  echo "$table"
  if ((WRITE_DOCS)); then write_block "$DOC" bench-table "$(printf "%s\n\n%s\n" "$header" "$table")"; fi
fi
if [[ " ${SELECTED[*]} " == *" mapping "* ]]; then
  runs=("$OUT"/mapping/*.json)
  if ((${#runs[@]})); then
    table=$(jq -n -r -L scripts -f scripts/mapping_table.jq "${runs[@]}")
    header="Generated by \`$mode --only mapping\` on $(date +%Y-%m-%d) ($(nproc) cores; load average $load_before before, $load_after after)."
    echo
    echo "$header"
    echo
    echo "$table"
    patrols=$(jq -n -r -L scripts -f scripts/patrol_table.jq "${runs[@]}")
    echo
    echo "$patrols"
    if ((WRITE_DOCS)); then
      write_block "$MAPPING_DOC" mapping-table "$(printf "%s\n\n%s\n" "$header" "$table")"
      write_block "$MAPPING_DOC" patrol-table "$(printf "%s\n\n%s\n" "$header" "$patrols")"
      mkdir -p docs/images/mapping
      cp "$OUT"/mapping/*.png docs/images/mapping/  # the table links each run's image there
    fi
  fi
fi

if [[ " ${SELECTED[*]} " == *" logs "* ]] && [ -n "$LOGS_DIR" ]; then
  runs=("$OUT"/logs/*.json)
  if ((${#runs[@]})); then
    table=$(jq -n -r -f scripts/logs_table.jq "${runs[@]}")
    header="Generated by \`$mode --only logs\` on $(date +%Y-%m-%d) ($(nproc) cores)."
    echo
    echo "$header"
    echo
    echo "$table"
    if ((WRITE_DOCS)); then
      write_block "$MAPPING_DOC" logs-table "$(printf "%s\n\n%s\n" "$header" "$table")"
      mkdir -p docs/images/logs
      cp "$OUT"/logs/*.png docs/images/logs/
    fi
  fi
fi

if ((${#failed[@]})); then
  echo "bench: failed: ${failed[*]}" >&2
  exit 1
fi

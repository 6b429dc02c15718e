#!/usr/bin/env bash
# Compares two slam-mapper builds with eval_mapping in the same conditions: for each of the four
# worlds that decide the pose-correction work (rooms, office, track at the default drift; office at
# drift 0) and each repeat, the BASE mapper and this build's run at the same time, so machine load
# hits both alike. 3 v1 robots, 20 simulated minutes at speed 4: about 5.5 minutes per pair, so
# the default (2 repeats) takes about 45 minutes. Prints one line per run; JSON, images and mapper
# logs go to OUT/base-N and OUT/this-N.
#
#   tests/bench/eval_mapping_pairs.sh BASE_MAPPER [REPEATS] [OUT]
#   e.g. tests/bench/eval_mapping_pairs.sh /path/to/main/build/bin/slam-mapper 2 build/bench/pairs
#
# EXTRA_WORLDS=twice adds the office at twice the drift (another 5.5 minutes per repeat); DURATION=S
# runs S simulated seconds instead of 1200.
set -euo pipefail
cd "$(dirname "$0")/../.."

base=${1:?usage: eval_mapping_pairs.sh BASE_MAPPER [REPEATS] [OUT]}
repeats=${2:-2}
out=${3:-build/bench/pairs}
duration=${DURATION:-1200}  # simulated seconds per run (a short one checks the set-up)
eval_bin=build/bin/eval_mapping
[[ -x $eval_bin ]] || { echo "build first: $eval_bin missing" >&2; exit 1; }
[[ -x $base ]] || { echo "no executable mapper at $base" >&2; exit 1; }
mkdir -p "$out"

worlds=(
  "--world rooms"
  "--world office"
  "--world track"
  "--world office --drift 0 --sim-arg=--heading-drift --sim-arg=0"
)
[[ ${EXTRA_WORLDS:-} == twice ]] && worlds+=("--world office --drift 0.04 --sim-arg=--heading-drift --sim-arg=0.02")

summary() {  # one line from an eval_mapping JSON
  jq -r '[.name, (.ate_corrected.rmse_m * 1000 | round / 10), (.ate_corrected.max_m * 100 * 10 | round / 10),
          (.map.near_wall_share * 1000 | round / 10), (.map.wall_found_share * 1000 | round / 10),
          .closures.false_closures, (.achieved_speed * 100 | round / 100)]
         | "\(.[0]): ATE RMSE \(.[1]) cm, max \(.[2]) cm, near a wall \(.[3]) %, walls found \(.[4]) %, false closures \(.[5]), speed \(.[6])"' "$1"
}

for ((r = 1; r <= repeats; ++r)); do
  for w in "${worlds[@]}"; do
    echo "== repeat $r: $w ($(uptime | sed 's/.*load average/load/'))"
    # shellcheck disable=SC2086  # each world's arguments are split on purpose
    $eval_bin $w --protocol v1 --speed 4 --duration "$duration" --mapper-bin "$base" --out "$out/base-$r" \
      >/dev/null 2>"$out.base.log" &
    base_pid=$!
    # shellcheck disable=SC2086
    $eval_bin $w --protocol v1 --speed 4 --duration "$duration" --out "$out/this-$r" >/dev/null 2>"$out.this.log" &
    this_pid=$!
    wait "$base_pid" || echo "base run failed: $(tail -n 3 "$out.base.log")"
    wait "$this_pid" || echo "this build's run failed: $(tail -n 3 "$out.this.log")"
    name=$(ls -t "$out/this-$r"/*.json | head -n 1)
    echo "  base: $(summary "$out/base-$r/$(basename "$name")")"
    echo "  this: $(summary "$name")"
  done
done

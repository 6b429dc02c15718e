# Turns the Google Benchmark JSON files of scripts/bench.sh (build/bench/bench_<name>.json, given
# as inputs) into the table of docs/performance.md: figure | measured | target | met.
# This file is the one place that maps benchmark names and counters to figures and targets.
#
# A figure: bench (file bench_<bench>.json), name (the benchmark as --benchmark_list_tests prints
# it; with repetitions the median is used), field ("cpu_time"/"real_time" in seconds, or a counter;
# an array shows several values joined by " / "), scale and unit for display, and an optional
# target {op, value (in display units), text}. {ratio: [id_a, id_b]} divides two earlier figures.

def figures: [
  {fig: "protocol: decode_v1, 16 / 360 / 4096 points per message", bench: "protocol",
   name: ["BM_DecodeV1/16", "BM_DecodeV1/360", "BM_DecodeV1/4096"], field: "cpu_time", scale: 1e6, unit: "µs",
   target: {op: "<=", value: 10, text: "≤ 10 µs each (≥ 100k msg/s per core)"}},
  {fig: "protocol: decode_v2_scan, 360 beams", bench: "protocol", name: "BM_DecodeV2Scan/360",
   field: "cpu_time", scale: 1e6, unit: "µs"},

  {fig: "mapper: ray casting, 1–5 m rays at 5 cm", bench: "mapper", name: "BM_TraceRay",
   field: "cells_per_s", scale: 1e-6, unit: "M cells/s", target: {op: ">=", value: 200, text: "≥ 200 M cells/s"}},
  {fig: "mapper: ingest, 360-beam scans", bench: "mapper", name: "BM_IntegrateScans/360",
   field: "points_per_s", scale: 1e-6, unit: "M points/s", target: {op: ">=", value: 1, text: "≥ 1 M points/s"}},
  {fig: "mapper: ingest, 4-point v1 messages", bench: "mapper", name: "BM_IntegrateScans/4",
   field: "points_per_s", scale: 1e-6, unit: "M points/s", target: {op: ">=", value: 1, text: "≥ 1 M points/s"}},
  {fig: "mapper: rebuild of 1 M observations at 10 cm (wall, reader thread + ray casting)", bench: "mapper", name: "BM_Rebuild1M/10/iterations:3",
   field: "real_time", scale: 1, unit: "s", target: {op: "<=", value: 1, text: "≤ 1 s"}},
  {fig: "mapper: rebuild of 1 M observations at 5 cm (wall, reader thread + ray casting)", bench: "mapper", name: "BM_Rebuild1M/5/iterations:3",
   field: "real_time", scale: 1, unit: "s", target: {op: "<=", value: 1, text: "≤ 1 s"}},
  {fig: "mapper: re-render after one small closure, 100 k / 400 k observations: full (CPU)", bench: "mapper",
   name: ["BM_RerenderFull/100000/iterations:3", "BM_RerenderFull/400000/iterations:3"],
   field: "cpu_time", scale: 1e3, unit: "ms"},
  {fig: "mapper: re-render after one small closure, 100 k / 400 k observations: partial (CPU)", bench: "mapper",
   name: ["BM_RerenderPartial/100000/iterations:10", "BM_RerenderPartial/400000/iterations:10"],
   field: "cpu_time", scale: 1e3, unit: "ms"},

  {fig: "planner: A* corner to corner, 1024² map (CPU)", bench: "planner", name: "BM_AstarCornerToCorner/repeats:5",
   field: "cpu_time", scale: 1e3, unit: "ms", target: {op: "<=", value: 20, text: "≤ 20 ms"}},
  {fig: "planner: RRTConnect + simplify (CPU)", bench: "planner",
   name: "BM_OmplCornerToCorner/rrtconnect/iterations:20/repeats:3",
   field: "cpu_time", scale: 1e3, unit: "ms", target: {op: "<=", value: 50, text: "≤ 50 ms"}},
  {fig: "planner: RRTConnect length ÷ A* length", bench: "planner",
   name: "BM_OmplCornerToCorner/rrtconnect/iterations:20/repeats:3",
   field: "length_ratio_to_astar", scale: 1, unit: "", target: {op: "<=", value: 1.1, text: "≤ 1.10"}},
  {fig: "planner: frontier extraction, full map (CPU)", bench: "planner", name: "BM_FrontierExtraction/repeats:5",
   field: "cpu_time", scale: 1e3, unit: "ms", target: {op: "<=", value: 5, text: "≤ 5 ms"}},
  {fig: "planner: re-plans for 100 robots, legs ≤ 10 m", bench: "planner", name: "BM_Replans100Robots/10",
   field: "replans_per_s", scale: 1, unit: "/s"},

  {fig: "simulator: 500 robots × 16 beams at 10 Hz", bench: "simulator", name: "BM_FleetTick/500/16",
   field: "core_share_at_10Hz", scale: 1, unit: "of a core", target: {op: "<", value: 0.5, text: "< 0.5 of a core"}},

  {fig: "slam: keyframe match, 100 points, ±0.15 m / ±0.08 rad, 400² grid at 5 cm (CPU)", bench: "slam",
   name: "BM_KeyframeMatch", field: "items_per_second", scale: 1, unit: "matches/s",
   target: {op: ">=", value: 500, text: "≥ 500 matches/s (≤ 2 ms each)"}},
  {fig: "slam: loop-closure match, 100 points, ±1 m / ±0.3 rad (CPU)", bench: "slam",
   name: "BM_LoopClosureMatch", field: "cpu_time", scale: 1e3, unit: "ms"},
  {fig: "slam: refining a match against 60 keyframes' points (CPU)", bench: "slam",
   name: "BM_PointRefinement", field: "cpu_time", scale: 1e6, unit: "µs"},

  {id: "broker", fig: "gateway: (a) broker baseline, mosquitto → subscriber", bench: "gateway",
   name: "BM_BrokerBaseline/iterations:1/real_time", field: "items_per_second", scale: 1, unit: "msg/s"},
  {id: "gateway", fig: "gateway: (b) MQTT → gateway → DDS, sustained", bench: "gateway",
   name: "BM_GatewayThroughput/iterations:1/real_time", field: "items_per_second", scale: 1, unit: "msg/s"},
  {fig: "gateway: (b) ÷ (a)", ratio: ["gateway", "broker"], unit: "",
   target: {op: ">=", value: 0.9, text: "≥ 0.9"}},
  {fig: "gateway: (c) added p50 latency at 10k msg/s (`--batch-ms 0`)", bench: "gateway", name: "BM_GatewayLatency/iterations:1/real_time",
   field: "added_p50_us", scale: 1, unit: "µs", target: {op: "<=", value: 100, text: "≤ 100 µs"}},
  {fig: "gateway: (c) p99 publish → DDS sample at 10k msg/s (`--batch-ms 0`)", bench: "gateway",
   name: "BM_GatewayLatency/iterations:1/real_time", field: "p99_us", scale: 1e-3, unit: "ms",
   target: {op: "<=", value: 1, text: "≤ 1 ms"}},
  {fig: "gateway: (c) messages lost at 10k msg/s", bench: "gateway", name: "BM_GatewayLatency/iterations:1/real_time",
   field: "lost", scale: 1, unit: "", target: {op: "==", value: 0, text: "0"}},
  {fig: "gateway: RSS growth over the throughput run", bench: "gateway",
   name: "BM_GatewayThroughput/iterations:1/real_time", field: "gateway_rss_growth_kb", scale: 1e-3, unit: "MB",
   target: {op: "<=", value: 2, text: "flat (≤ 2 MB)"}},

  {fig: "viewer: steady frame p95, 1 M points (llvmpipe)", bench: "viewer",
   name: "BM_SteadyFrame/1000000/iterations:60/manual_time", field: "p95_ms", scale: 1, unit: "ms",
   target: {op: "<=", value: 33, text: "≤ 33 ms"}},
  {fig: "viewer: panning frame p95, 1 M points", bench: "viewer",
   name: "BM_PanFrame/1000000/iterations:60/manual_time", field: "p95_ms", scale: 1, unit: "ms",
   target: {op: "<=", value: 100, text: "≤ 100 ms"}},
  {fig: "viewer: steady / panning frame p95, 4 M points", bench: "viewer",
   name: ["BM_SteadyFrame/4000000/iterations:60/manual_time", "BM_PanFrame/4000000/iterations:60/manual_time"],
   field: "p95_ms", scale: 1, unit: "ms"},
  {fig: "viewer: full redraw after a pan, 100 k / 1 M / 4 M points", bench: "viewer",
   name: ["BM_PanFrame/100000/iterations:60/manual_time", "BM_PanFrame/1000000/iterations:60/manual_time",
          "BM_PanFrame/4000000/iterations:60/manual_time"], field: "resettle_ms", scale: 1, unit: "ms"},
  {fig: "viewer: worst frame re-rendering the points after a pan, robots streaming, 1 M / 4 M points", bench: "viewer",
   name: ["BM_RerenderFrame/1000000/0/iterations:6/manual_time", "BM_RerenderFrame/4000000/0/iterations:6/manual_time"],
   field: "max_frame_ms", scale: 1, unit: "ms", target: {op: "<=", value: 100, text: "≤ 100 ms"}},

  {fig: "pipeline: simulator sent (1000 robots × 10 Hz)", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: "sim_sent_per_s", scale: 1, unit: "msg/s",
   target: {op: ">=", value: 9900, text: "≥ 9 900 msg/s"}},
  {fig: "pipeline: gateway received ÷ simulator sent", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: "gateway_over_sim", scale: 1, unit: "",
   target: {op: ">=", value: 0.99, text: "≥ 0.99"}},
  {fig: "pipeline: mapper integrated ÷ gateway published", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: "mapper_over_gateway", scale: 1, unit: "",
   target: {op: ">=", value: 0.99, text: "≥ 0.99"}},
  {fig: "pipeline: mapper backlog at the end of the window", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: "mapper_backlog_end", scale: 1, unit: "obs",
   target: {op: "<=", value: 1000, text: "≤ 1 000 (0.1 s of traffic)"}},
  {fig: "pipeline: observations dropped by the mapper", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: "mapper_dropped", scale: 1, unit: "",
   target: {op: "==", value: 0, text: "0"}},
  {fig: "pipeline: messages dropped by mosquitto / batches lost by DDS before the mapper", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: ["broker_dropped", "mapper_dds_lost"], scale: 1, unit: "",
   target: {op: "==", value: 0, text: "0"}},
  {fig: "pipeline: map patches to each reader (GridTiles)", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: "patch_mb_per_s", scale: 1, unit: "MB/s",
   target: {op: "<=", value: 2, text: "≤ 2 MB/s"}},
  {fig: "pipeline: robot message → map patch delay, p50 / p99", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time", field: ["delay_p50_ms", "delay_p99_ms"], scale: 1, unit: "ms"},
  {fig: "pipeline: CPU % of a core: mosquitto / gateway / mapper / planner / simulator", bench: "pipeline",
   name: "BM_Pipeline/iterations:1/real_time",
   field: ["cpu_mosquitto_pct", "cpu_gateway_pct", "cpu_mapper_pct", "cpu_planner_pct", "cpu_simulator_pct"],
   scale: 1, unit: "%"}
];

# Three significant digits, thousands separated by a space (as the rest of the docs write them).
def fmt:
  if . == null then "—"
  else (if . < 0 then -1 else 1 end) as $sign | (. * $sign) as $a
    | (if $a >= 100 then ($a | round) elif $a >= 10 then ($a * 10 | round) / 10
       elif $a >= 1 then ($a * 100 | round) / 100 else ($a * 1000 | round) / 1000 end) as $r
    | ($r | floor | tostring | explode | reverse | [range(0; length; 3) as $i | .[$i:$i + 3]]
       | map(reverse | implode) | reverse | join(" ")) as $int
    | ($r | tostring | if test("\\.") then "." + (split(".")[1]) else "" end) as $frac
    | (if $sign < 0 then "-" else "" end) + $int + $frac
  end;

def seconds_per_unit: {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1}[.];

# The benchmark entry for `name` in `runs`: the median of repetitions when there are several.
def entry($runs; $bench; $name):
  ($runs[$bench].benchmarks // []) | map(select(.run_name == $name and (.error_occurred | not)))
  | (map(select(.aggregate_name == "median")) + map(select(.run_type == "iteration")))[0];

def value_of($runs; $f; $name):
  entry($runs; $f.bench; $name) as $e
  | if $e == null then null
    elif $f.field == "cpu_time" or $f.field == "real_time" then $e[$f.field] * ($e.time_unit | seconds_per_unit) * $f.scale
    else ($e[$f.field] // null) | if . == null then null else . * $f.scale end end;

def met($v; $t):
  if $t == null then "" elif $v == null then "—"
  elif ({"<=": ($v <= $t.value), "<": ($v < $t.value), ">=": ($v >= $t.value), "==": ($v == $t.value)}[$t.op])
  then "yes" else "**no**" end;

def unit_suffix: if . == "" then "" elif . == "%" then "%" else " " + . end;

reduce inputs as $doc ({}; . + {(input_filename | sub(".*/bench_"; "") | sub("\\.json$"; "")): $doc})
| . as $runs
| reduce figures[] as $f ({values: {}, rows: []};
    (if $f.ratio then
       (.values[$f.ratio[0]]) as $a | (.values[$f.ratio[1]]) as $b
       | (if $a != null and $b != null and $b != 0 then [$a / $b] else [null] end)
     elif ($f.name | type) == "array" then [$f.name[] as $n | value_of($runs; $f; $n)]
     elif ($f.field | type) == "array" then [$f.field[] as $field | value_of($runs; $f + {field: $field}; $f.name)]
     else [value_of($runs; $f; $f.name)] end) as $vals
    | (if ($vals | map(select(. == null)) | length) == ($vals | length) then "not run"
       else ($vals | map(fmt) | join(" / ")) + ($f.unit | unit_suffix) end) as $shown
    | (if $f.target == null then null
       elif ($vals | map(select(. == null)) | length) > 0 then null
       else ($vals | map(met(.; $f.target)) | if all(. == "yes") then "yes" else "**no**" end) end) as $met
    | .values[$f.id // ""] = $vals[0]
    | .rows += ["| \($f.fig) | \($shown) | \($f.target.text // "—") | \($met // (if $f.target then "—" else "" end)) |"])
| (["| figure | measured | target | met |", "| --- | --- | --- | --- |"] + .rows)[]

# The real-log table of docs/mapping-quality.md from eval_log's JSON files (scripts/bench.sh --only logs):
# one row per log and sensor set-up, the relation metric's mean ± std of the absolute errors for the final
# trajectory, the poses published while driving and raw odometry, and the short relations (<= 10 s).
def m: "\(.trans_abs_m.mean * 1000 | round / 1000) ± \(.trans_abs_m.std * 1000 | round / 1000) m, \(.rot_abs_deg.mean * 100 | round / 100)°";
def short: "\(.short.trans_abs_m.mean * 1000 | round / 1000)";
def setup: if .protocol == "v1" then "v1, \(.beams) beams ≤ \(.max_range_m) m"
  elif .beams > 0 then "\(.beams) beams ≤ \(.max_range_m) m" else "all beams ≤ \(.max_range_m) m" end;
[inputs] | sort_by(.name) |
("| log | robot | final trajectory | published while driving | raw odometry | short (≤ 10 s): final / published / odometry (m) | closures | speed |",
 "| --- | --- | --- | --- | --- | --- | --- | --- |",
 (.[] | "| \(.name | split("-")[0]) | \(setup) | \(.final.all | m) | \(.published.all | m) | \(.odometry.all | m) | \(.final | short) / \(.published | short) / \(.odometry | short) | \(.slam.closures_accepted) | \(.log_s / .wall_s | floor)× real time |"))

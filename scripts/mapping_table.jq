# Turns the eval_mapping results (BUILD/bench/mapping/*.json, one run each, given as inputs) into
# the table of docs/mapping-quality.md: one row per run (world, protocol, drift, SLAM), the
# trajectory, goal and map figures as columns, then the mapper's accepted loop closures and how many
# of them the truth shows false (a loop correction that moved a robot more than 10 cm further from
# its true pose). Rows sorted by world, protocol, drift, SLAM. Runs with a patrol after exploration
# (eval_mapping --patrol) have their own table: patrol_table.jq.

include "mapping_defs";

[inputs | select((.after_exploration // "idle") == "idle")] | sort_by(.world, .protocol, .drift, (.sim_args | join(" ")), .slam)
| (["| world | protocol | drift | SLAM | ATE corrected RMSE / max (cm) | ATE raw RMSE / max (cm) | goal mean / max (cm, n) | occupied near a wall | mean wall distance (cm) | walls found | reachable known free | closures | false closures | run |",
    "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
   + map("| \(.world) | \(.protocol) | \(drift) | \(.slam)\(if .aligned then " (aligned)" else "" end) "
       + "| \(pair(.ate_corrected.rmse_m; .ate_corrected.max_m)) | \(pair(.ate_raw.rmse_m; .ate_raw.max_m)) "
       + "| \(pair(.goal_true.mean_m; .goal_true.max_m)) (\(.goal_true.count)) "
       + "| \(.map.near_wall_share | pct) | \(.map.mean_wall_distance_m | cm) | \(.map.wall_found_share | pct) "
       + "| \(.map.coverage | pct) "
       + "| \(.slam_counters.slam_closures_accepted | count) | \(.closures.false_closures | count) "
       + "| \(.simulated_s / 60 | round) sim min at ×\(.achieved_speed * 10 | round / 10), [image](images/mapping/\(.image)) |"))[]
